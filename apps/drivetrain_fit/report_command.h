// drivetrain-fit report: derived quantities of a parameter file.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace driveid::cli {

struct ReportOptions {
  std::string params;
  std::string fitted;
  std::vector<double> pose;      ///< x, y [m] for the robot report
  std::vector<double> velocity;  ///< vx, vy [m/s]
  bool json = false;
};

CLI::App* SetupReportCommand(CLI::App& app, ReportOptions& options);
void RunReportCommand(const ReportOptions& options);

}  // namespace driveid::cli
