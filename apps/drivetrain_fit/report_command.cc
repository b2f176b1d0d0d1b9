#include "drivetrain_fit/report_command.h"

#include <optional>

#include <fmt/format.h>

#include "common/cli_support.h"
#include "common/command_registry.h"
#include "params/parameter_file.h"
#include "workflow/parameter_report.h"

namespace driveid::cli {

CLI::App* SetupReportCommand(CLI::App& app, ReportOptions& options) {
  CLI::App* command = app.add_subcommand(
      "report", "Transfer function (eq. 16), omega_n, zeta, gain; the paper's eq. (17) beside the recomputed values; "
      "a fitted axis' feed-forward gains (docs/models.md#feed-forward)");
  command->add_option("params", options.params, "parameter file")->required();
  command->add_option("--fitted", options.fitted,
                      "a fitted parameter file: beside a drivetrain section its values in a further column, "
                      "else its fit.estimates compared with the file's (both must be fits)");
  command->add_option("--pose", options.pose, "robot: centre joint x,y [m] (default: the workspace centre)")
      ->delimiter(',')
      ->expected(2);
  command->add_option("--velocity", options.velocity, "robot: centre joint velocity vx,vy [m/s] for C (default 0)")
      ->delimiter(',')
      ->expected(2);
  command->add_flag("--json", options.json, "print one JSON object instead of the text");
  command->footer("Example:\n  drivetrain-fit report data/paper000.yaml --fitted out/fig6_fit.yaml");
  return command;
}

void RunReportCommand(const ReportOptions& options) {
  const ParameterFile file = ReadParameterFile(options.params);
  ParameterReportRequest request;
  request.path = options.params;
  std::optional<ParameterFile> fitted;
  if (!options.fitted.empty()) {
    fitted = ReadParameterFile(options.fitted);
    request.fitted = &*fitted;
    request.fitted_path = options.fitted;
  }
  if (options.pose.size() == 2) request.pose = Vector2{options.pose[0], options.pose[1]};
  if (options.velocity.size() == 2) request.velocity = Vector2{options.velocity[0], options.velocity[1]};
  const ParameterReport report = ReportParameterFile(file, request, options.json);
  WriteStdout(options.json ? DumpJson(report.json) : report.text);
}

namespace {
const bool kRegistered = RegisterCommand(Command<ReportOptions>(
    "drivetrain-fit", "", 50, [](CLI::App& parent, ReportOptions& o) { return SetupReportCommand(parent, o); },
    [](const ReportOptions& o, const std::string&) { RunReportCommand(o); }));
}  // namespace

}  // namespace driveid::cli
