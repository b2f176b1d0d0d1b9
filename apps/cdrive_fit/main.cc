// cdrive-fit: identification and simulation of the two-motor ball-screw
// C-drive (seed 001). Wiring only; the work is in lib/.
#include <CLI/CLI.hpp>

#include "cdrive_fit/fit_command.h"
#include "cdrive_fit/report_command.h"
#include "cdrive_fit/simulate_command.h"
#include "common/cli_support.h"

int main(int argc, char** argv) {
  using namespace driveid::cli;
  CLI::App app{"Identify and simulate the C-drive (driveid " DRIVEID_VERSION ")", "cdrive-fit"};
  app.set_version_flag("--version", DRIVEID_VERSION);
  app.require_subcommand(1);
  CDriveFitCommandOptions friction, inertia;
  CDriveReportOptions report;
  CDriveSimulateOptions simulate;
  CLI::App* friction_command = SetupCDriveFitCommand(app, friction, CDriveFitKind::kFriction);
  CLI::App* inertia_command = SetupCDriveFitCommand(app, inertia, CDriveFitKind::kInertia);
  CLI::App* report_command = SetupCDriveReportCommand(app, report);
  CLI::App* simulate_command = SetupCDriveSimulateCommand(app, simulate);
  const std::string command_line = CommandLine(argc, argv);
  return RunMain(app, argc, argv, [&] {
    if (*friction_command) RunCDriveFitCommand(friction, command_line);
    if (*inertia_command) RunCDriveFitCommand(inertia, command_line);
    if (*report_command) RunCDriveReportCommand(report);
    if (*simulate_command) RunCDriveSimulateCommand(simulate, command_line);
  });
}
