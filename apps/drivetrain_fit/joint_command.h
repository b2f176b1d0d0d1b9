// drivetrain-fit joint: the elastic two-mass joint (docs/models.md#elastic-joint).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/cli_support.h"
#include "common/log_input_options.h"
#include "models/joint.h"

namespace driveid::cli {

struct JointOptions {
  std::vector<std::string> logs;
  std::string params;
  std::vector<std::string> free;  ///< empty: the default for the logs (JointDefaultFree)
  LogInputCli input;
  double cutoff = 0.0;
  std::string method = "auto";  ///< auto, id, oe
  std::string segment = "auto";  ///< output error: auto, none or seconds
  FitOutputOptions output;
};

CLI::App* SetupJointCommand(CLI::App& app, JointOptions& options);
void RunJointCommand(const JointOptions& options, const std::string& command_line);

}  // namespace driveid::cli
