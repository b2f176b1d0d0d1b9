#include "drivetrain_fit/report_command.h"

#include <cstdio>

#include <fmt/format.h>

#include "core/errors.h"
#include "io/parameter_file.h"
#include "report/drivetrain_report.h"

namespace driveid::cli {

CLI::App* SetupReportCommand(CLI::App& app, ReportOptions& options) {
  CLI::App* command = app.add_subcommand(
      "report", "Transfer function (eq. 16), omega_n, zeta, gain; the paper's eq. (17) beside the recomputed values");
  command->add_option("params", options.params, "parameter file")->required();
  command->add_option("--fitted", options.fitted, "a fitted parameter file to show in a further column");
  command->add_flag("--json", options.json, "print one JSON object instead of the text");
  command->footer("Example:\n  drivetrain-fit report data/paper000.yaml --fitted out/fig6_fit.yaml");
  return command;
}

void RunReportCommand(const ReportOptions& options) {
  const ParameterFile file = ReadParameterFile(options.params);
  if (!file.drivetrain) throw InputError(fmt::format("{}: no 'drivetrain' section", options.params));
  ParameterFile fitted;
  if (!options.fitted.empty()) {
    fitted = ReadParameterFile(options.fitted);
    if (!fitted.drivetrain) throw InputError(fmt::format("{}: no 'drivetrain' section", options.fitted));
  }
  const DriveTrainParameters* fitted_params = fitted.drivetrain ? &*fitted.drivetrain : nullptr;
  const std::string text = options.json
                               ? FormatDriveTrainReportJson(*file.drivetrain, options.params, fitted_params)
                               : FormatDriveTrainReport(*file.drivetrain, options.params, fitted_params, options.fitted);
  std::fputs(text.c_str(), stdout);
}

}  // namespace driveid::cli
