// drivetrain-fit simulate step: synthetic step logs in the input format.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "workflow/synthetic_logs.h"

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
  std::string reference;  ///< --reference: follow this file instead of a profile
  AxisExperiment experiment;
};

struct SimulateRobotOptions {
  std::string params;
  std::string output;
  RobotExperiment experiment;
};

struct SimulateJointOptions {
  std::string params;
  std::string output;
  std::vector<double> band;
  std::string reference;          ///< --reference: an injected excitation (t,tau)
  bool duration_given = false;    ///< --duration given (else the reference's length)
  JointExperiment experiment;
};

/// Each declares its subcommand on the `simulate` group.
CLI::App* SetupSimulateStepCommand(CLI::App& simulate, SimulateStepOptions& options);
CLI::App* SetupSimulateAxisCommand(CLI::App& simulate, SimulateAxisOptions& options);
CLI::App* SetupSimulateRobotCommand(CLI::App& simulate, SimulateRobotOptions& options);
void RunSimulateRobotCommand(const SimulateRobotOptions& options, const std::string& command_line);
void RunSimulateStepCommand(const SimulateStepOptions& options, const std::string& command_line);
void RunSimulateAxisCommand(const SimulateAxisOptions& options, const std::string& command_line);
CLI::App* SetupSimulateJointCommand(CLI::App& simulate, SimulateJointOptions& options);
void RunSimulateJointCommand(const SimulateJointOptions& options, const std::string& command_line);

}  // namespace driveid::cli
