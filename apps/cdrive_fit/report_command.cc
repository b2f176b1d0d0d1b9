#include "cdrive_fit/report_command.h"

#include <cstdio>

#include <fmt/format.h>

#include "common/cli_support.h"
#include "common/command_registry.h"
#include "core/errors.h"
#include "params/parameter_file.h"
#include "report/cdrive_report.h"
#include "report/feedforward_report.h"

namespace driveid::cli {

CLI::App* SetupCDriveReportCommand(CLI::App& app, CDriveReportOptions& options) {
  CLI::App* command = app.add_subcommand(
      "report", "Jacobian, its inverse, isotropy, inertia matrix, a Table-I style table of the dissipation parameters and "
      "a fitted file's eq. (31) compensation block");
  command->add_option("params", options.params, "parameter file with a cdrive section")->required();
  command->add_flag("--json", options.json, "print one JSON object instead of the text");
  command->footer("Example:\n  cdrive-fit report data/cdrive_table1.yaml");
  return command;
}

void RunCDriveReportCommand(const CDriveReportOptions& options) {
  const ParameterFile file = ReadParameterFile(options.params);
  if (!file.Find<CDriveSection>()) throw InputError(fmt::format("{}: no 'cdrive' section", options.params));
  const CDriveReport report = CalcCDriveReport(*file.Find<CDriveSection>(), file.Find<CDriveControlSection>(), file.fit_estimates, options.params);
  if (options.json) {
    Json json = CDriveReportJson(report);
    if (!file.feedforward.gains.empty()) json["compensation"] = FeedforwardReportJson(file.feedforward);
    WriteStdout(DumpJson(json));
  } else {
    // The eq. (31) block a friction fit wrote, with its uncertainty.
    WriteStdout(FormatCDriveReport(report) +
                (file.feedforward.gains.empty() ? "" : "\n" + FormatFeedforwardReport(file.feedforward)));
  }
}

namespace {
const bool kRegistered = RegisterCommand(Command<CDriveReportOptions>(
    "cdrive-fit", "", 30, [](CLI::App& parent, CDriveReportOptions& o) { return SetupCDriveReportCommand(parent, o); },
    [](const CDriveReportOptions& o, const std::string&) { RunCDriveReportCommand(o); }));
}  // namespace

}  // namespace driveid::cli
