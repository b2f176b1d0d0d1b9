#include "common/validation_output.h"

#include <fmt/format.h>

#include "system/atomic_file.h"
#include "report/fit_summary.h"
#include "report/plot.h"
#include "workflow/validation_run.h"

namespace driveid::cli {

void AddValidationOutputOptions(CLI::App& command, FitOutputOptions& options) {
  command.add_option("--trace", options.trace, "write a CSV of time, measured, predicted and residual per log");
  command.add_option("--plot", options.plot, "render measured vs predicted and residuals (.png or .svg)")
      ->check(PlotPath());
  command.add_flag("--json", options.json, "print the result as one JSON object instead of the table");
  command.add_flag("-q,--quiet", options.quiet, "print no table");
  command.add_option("--max-log-size", options.max_log_gib, "largest log to read [GiB]")
      ->capture_default_str()
      ->check(FiniteWithin(1e-6, 1024.0));
  command.add_option("--fail-below", options.fail_below,
                     "a quality gate: exit 1 (after the report) when a log's fit % is below PCT, or has none "
                     "(docs/formats.md#exit-codes)")
      ->type_name("PCT")
      ->check(FiniteWithin(-1e6, 100.0));
}

void EmitValidation(const FitOutputOptions& options, const ValidationReport& report,
                    const std::vector<ValidatedLog>& logs) {
  const ValidationOutputs made = AssembleValidationOutputs(report.program, report.method, logs);
  const std::vector<ChannelStatistics>& stats = made.stats;
  std::vector<std::pair<std::string, std::string>> files;
  if (!options.plot.empty()) {
    files.emplace_back(options.plot, RenderPanels(options.plot, MakeFitPanels(made.series, {report.title, report.unit}),
                                                  "time [s]"));
  }
  if (!options.trace.empty()) files.emplace_back(options.trace, made.trace_csv);
  WriteFilesAtomically(files, [&] {
    if (options.json) {
      Json document = {{"command", report.command_line}, {"version", DRIVEID_VERSION}, {"model", report.method}};
      document["logs"] = ValidationJson(stats);
      WriteStdout(DumpJson(document));
    } else if (!options.quiet) {
      WriteStdout(fmt::format("{}\n{}", report.method, FormatValidationTable(stats)));
    }
  });
  if (options.fail_below) {
    const std::vector<std::string> below = LogsBelowFit(stats, *options.fail_below);
    if (!below.empty()) {
      throw GateFailed{fmt::format("fit below {:g} %: {}", *options.fail_below, fmt::join(below, ", "))};
    }
  }
}

}  // namespace driveid::cli
