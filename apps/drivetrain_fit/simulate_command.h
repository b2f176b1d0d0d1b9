// drivetrain-fit simulate step: synthetic step logs in the input format.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "sim/step_experiment.h"

namespace driveid::cli {

struct SimulateStepOptions {
  std::string params;
  std::string output;
  std::string model = "reduced";
  StepExperiment experiment;
};

CLI::App* SetupSimulateCommand(CLI::App& app, SimulateStepOptions& options);
void RunSimulateStepCommand(const SimulateStepOptions& options, const std::string& command_line);

}  // namespace driveid::cli
