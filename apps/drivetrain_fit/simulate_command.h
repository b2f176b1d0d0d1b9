// drivetrain-fit simulate step: synthetic step logs in the input format.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "sim/axis_experiment.h"
#include "sim/robot_experiment.h"
#include "sim/step_experiment.h"

namespace driveid::cli {

struct SimulateStepOptions {
  std::string params;
  std::string output;
  std::string model = "reduced";
  StepExperiment experiment;
};

struct SimulateAxisOptions {
  std::string params;
  std::string output;
  AxisExperiment experiment;
};

struct SimulateRobotOptions {
  std::string params;
  std::string output;
  RobotExperiment experiment;
};

struct SimulateCommands {
  CLI::App* step = nullptr;
  CLI::App* axis = nullptr;
  CLI::App* robot = nullptr;
};

SimulateCommands SetupSimulateCommand(CLI::App& app, SimulateStepOptions& step, SimulateAxisOptions& axis,
                                      SimulateRobotOptions& robot);
void RunSimulateRobotCommand(const SimulateRobotOptions& options, const std::string& command_line);
void RunSimulateStepCommand(const SimulateStepOptions& options, const std::string& command_line);
void RunSimulateAxisCommand(const SimulateAxisOptions& options, const std::string& command_line);

}  // namespace driveid::cli
