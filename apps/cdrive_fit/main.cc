// cdrive-fit: identification and simulation of the two-motor ball-screw
// C-drive (seed 001). Wiring only: each subcommand registers itself in its
// own file (common/command_registry.h); the work is in lib/.
#include <CLI/CLI.hpp>

#include "common/cli_support.h"
#include "common/command_registry.h"

int main(int argc, char** argv) {
  using namespace driveid::cli;
  CLI::App app{"Identify and simulate the C-drive (driveid " DRIVEID_VERSION ")", "cdrive-fit"};
  app.set_version_flag("--version", DRIVEID_VERSION);
  app.require_subcommand(1);
  const auto run = SetupCommands(app, "cdrive-fit");
  const std::string command_line = CommandLine(argc, argv);
  return RunMain(app, argc, argv, [&] { run(command_line); });
}
