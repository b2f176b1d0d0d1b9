// drivetrain-fit axis: IDIM-LS identification of a rigid axis (docs/models.md#axis).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/cli_support.h"
#include "common/log_input_options.h"
#include "workflow/axis_identification.h"
#include "logs/csv_log.h"
#include "models/axis.h"

namespace driveid::cli {

struct AxisOptions {
  std::vector<std::string> logs;
  std::string params;
  LogInputCli input;
  std::string method = "auto";  ///< auto, idim, oe
  /// --free, --cutoff, --decimation: the fit's own options, handed down as
  /// they are (the torque timing and progress are set from the flags below).
  AxisFitOptions fit = AxisFitOptionsFromData();
  std::string torque_timing = "auto";
  std::vector<std::string> validate;  ///< held-out logs predicted by the fit
  bool linear = false;                ///< q in m, forces in N (or axis.linear in --params)
  FitOutputOptions output;
};

CLI::App* SetupAxisCommand(CLI::App& app, AxisOptions& options);
void RunAxisCommand(const AxisOptions& options, const std::string& command_line);

/// What `axis` computes before it emits, for the command and the Python
/// module alike: the outputs and the summary lines printed after the table.
struct AxisCommandResult {
  FitOutputs outputs;
  std::vector<std::string> summary;
};
/// `given`: logs already in memory, each with AxisLogColumns()' columns (the
/// Python module's arrays), read in place of options.logs when not empty.
AxisCommandResult ComputeAxisCommand(const AxisOptions& options, const std::string& command_line,
                                     std::vector<CsvLog> given = {});

}  // namespace driveid::cli
