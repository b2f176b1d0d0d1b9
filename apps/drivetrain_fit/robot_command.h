// drivetrain-fit robot: Theta, m_c, d_g of the planar robot (docs/models.md#planar-robot).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/cli_support.h"
#include "common/log_input_options.h"
#include "models/planar_robot.h"
#include "workflow/serial_robot_identification.h"

namespace driveid::cli {

struct RobotOptions {
  std::vector<std::string> logs;
  std::string params;
  std::string urdf;  ///< a serial robot (docs/models.md#serial-robot) instead of the planar one
  double prior_weight = kConsistentPriorWeight;
  std::vector<std::string> per_direction;  ///< --urdf: joints with viscous friction per direction
  std::vector<std::string> free = FitParameterKeys(PlanarRobotParameterTable(), "robot", true);
  const CLI::Option* free_option = nullptr;  ///< whether --free was given (with --urdf its default is all)
  LogInputCli input;
  double window = 0.0;  ///< 0: 0.005 s (planar robot), 0.05 s (--urdf)
  FitOutputOptions output;
};

CLI::App* SetupRobotCommand(CLI::App& app, RobotOptions& options);
void RunRobotCommand(const RobotOptions& options, const std::string& command_line);

}  // namespace driveid::cli
