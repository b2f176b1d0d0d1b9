// drivetrain-fit: identification of the elastic geared drive train of the
// planar parallel robot (seed 000). Wiring only; the work is in lib/.
#include <CLI/CLI.hpp>

#include "common/cli_support.h"
#include "drivetrain_fit/axis_command.h"
#include "drivetrain_fit/report_command.h"
#include "drivetrain_fit/robot_command.h"
#include "drivetrain_fit/simulate_command.h"
#include "drivetrain_fit/step_command.h"

int main(int argc, char** argv) {
  using namespace driveid::cli;
  CLI::App app{"Identify drive-train parameters from logged data (driveid " DRIVEID_VERSION ")", "drivetrain-fit"};
  app.set_version_flag("--version", DRIVEID_VERSION);
  app.require_subcommand(1);
  StepOptions step;
  SimulateStepOptions simulate;
  SimulateAxisOptions simulate_axis;
  SimulateRobotOptions simulate_robot;
  RobotOptions robot;
  ReportOptions report;
  AxisOptions axis;
  CLI::App* step_command = SetupStepCommand(app, step);
  CLI::App* axis_command = SetupAxisCommand(app, axis);
  CLI::App* robot_command = SetupRobotCommand(app, robot);
  const SimulateCommands simulate_commands = SetupSimulateCommand(app, simulate, simulate_axis, simulate_robot);
  CLI::App* report_command = SetupReportCommand(app, report);
  const std::string command_line = CommandLine(argc, argv);
  return RunMain(app, argc, argv, [&] {
    if (*step_command) RunStepCommand(step, command_line);
    if (*axis_command) RunAxisCommand(axis, command_line);
    if (*simulate_commands.step) RunSimulateStepCommand(simulate, command_line);
    if (*simulate_commands.axis) RunSimulateAxisCommand(simulate_axis, command_line);
    if (*robot_command) RunRobotCommand(robot, command_line);
    if (*simulate_commands.robot) RunSimulateRobotCommand(simulate_robot, command_line);
    if (*report_command) RunReportCommand(report);
  });
}
