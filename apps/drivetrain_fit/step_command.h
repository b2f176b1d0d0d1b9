// drivetrain-fit step: output-error fit of the drive train to step logs.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/cli_support.h"
#include "common/log_input_options.h"
#include "models/drivetrain.h"

namespace driveid::cli {

struct StepOptions {
  std::vector<std::string> logs;
  std::string params;
  std::string model = "reduced";
  std::string starts = "staged";
  std::string integrator = "exact";
  std::vector<std::string> free = FitParameterKeys(DriveTrainParameterTable(), "step", true);
  LogInputCli input;
  std::vector<std::string> validate;  ///< held-out logs predicted by the fit
  FitOutputOptions output;
};

CLI::App* SetupStepCommand(CLI::App& app, StepOptions& options);
void RunStepCommand(const StepOptions& options, const std::string& command_line);

}  // namespace driveid::cli
