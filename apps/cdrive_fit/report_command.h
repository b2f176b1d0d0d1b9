// cdrive-fit report: kinematics, inertia and dissipation of a parameter file.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace driveid::cli {

struct CDriveReportOptions {
  std::string params;
  bool json = false;
};

CLI::App* SetupCDriveReportCommand(CLI::App& app, CDriveReportOptions& options);
void RunCDriveReportCommand(const CDriveReportOptions& options);

}  // namespace driveid::cli
