// Output of `validate` in both tools (docs/models.md#validation): the plot of
// measured vs predicted with residuals, the trace CSV (written together,
// atomically), and the per-log table or one JSON object on stdout.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/cli_support.h"
#include "workflow/validation_run.h"

namespace driveid::cli {

/// Adds --trace, --plot, --json, -q and --max-log-size (validate writes no parameter file).
void AddValidationOutputOptions(CLI::App& command, FitOutputOptions& options);

struct ValidationReport {
  std::string program;       ///< "drivetrain-fit"
  std::string command_line;
  std::string method;        ///< how the logs were predicted, for the table, trace and JSON
  std::string title, unit;   ///< of the plot
};

void EmitValidation(const FitOutputOptions& options, const ValidationReport& report,
                    const std::vector<ValidatedLog>& logs);

}  // namespace driveid::cli
