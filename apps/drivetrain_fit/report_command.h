// drivetrain-fit report: derived quantities of a parameter file.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace driveid::cli {

struct ReportOptions {
  std::string params;
  std::string fitted;
  bool json = false;
};

CLI::App* SetupReportCommand(CLI::App& app, ReportOptions& options);
void RunReportCommand(const ReportOptions& options);

}  // namespace driveid::cli
