// drivetrain-fit validate: predict logs from a parameter file and report how
// well the prediction matches (docs/models.md#validation).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/cli_support.h"
#include "common/log_input_options.h"
#include "workflow/axis_identification.h"

namespace driveid::cli {

struct ValidateOptions {
  std::string params;
  std::vector<std::string> logs;
  std::string model;              ///< "axis", "step", "joint", "robot"; "" = from the parameter file's sections
  std::string urdf;               ///< a serial robot's URDF instead of the one its file names
  std::string step_model = "reduced";
  LogInputCli input;
  double cutoff = 0.0;
  int decimation = kAxisDecimationFromLogs;
  std::string torque_timing = "file";
  bool simulate = false;          ///< axis: position by simulation instead of torque by inverse dynamics
  std::string joint = "axis";     ///< MJCF: the joint driven by the logged effort
  double mujoco_step = 1e-3;      ///< MJCF: largest MuJoCo time step [s]
  double window = 0.0;            ///< robot MJCF: differentiator half window [s] (0: the fit's default)
  FitOutputOptions output;        ///< --plot, --trace, --json, -q, --max-log-size (no -o)
};

CLI::App* SetupValidateCommand(CLI::App& app, ValidateOptions& options);
void RunValidateCommand(const ValidateOptions& options, const std::string& command_line);

}  // namespace driveid::cli
