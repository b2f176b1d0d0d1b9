// cdrive-fit friction | inertia: inverse-dynamics fits of the C-drive.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/cli_support.h"
#include "common/log_input_options.h"
#include "workflow/cdrive_identification.h"

namespace driveid::cli {

struct CDriveFitCommandOptions {
  CDriveFitKind kind = CDriveFitKind::kFriction;
  std::vector<std::string> logs;
  std::string params;
  std::vector<std::string> free;
  LogInputCli input;
  double window = 0.0;     ///< differentiator half window [s]; 0 = the fit's default
  double min_rate = 0.5;   ///< [rad/s]
  double settle = -1.0;    ///< [s]; < 0 = the fit's default
  FitOutputOptions output;
};

CLI::App* SetupCDriveFitCommand(CLI::App& app, CDriveFitCommandOptions& options, CDriveFitKind kind);
void RunCDriveFitCommand(const CDriveFitCommandOptions& options, const std::string& command_line);

}  // namespace driveid::cli
