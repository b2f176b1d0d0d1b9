// cdrive-fit simulate: closed-loop simulation of a Table II motion program.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace driveid::cli {

struct CDriveSimulateOptions {
  std::string program;
  std::string params;
  std::string output;
  std::string trace;
  std::string plot;
  std::string law;  ///< override of cdrive.control.law
  double stroke = 1.0;
  int cycles = 1;
  double noise = 0.0;
  unsigned long seed = 1;
  bool json = false;
};

CLI::App* SetupCDriveSimulateCommand(CLI::App& app, CDriveSimulateOptions& options);
void RunCDriveSimulateCommand(const CDriveSimulateOptions& options, const std::string& command_line);

}  // namespace driveid::cli
