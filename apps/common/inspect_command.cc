// `inspect LOG...`: what the tools would read from a log file — columns,
// samples, rate and jitter, time span, ranges, segments, and the
// expressions and crops applied (docs/formats.md#logs). Registered in both
// tools; the first command a new user runs on their own data.
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/cli_support.h"
#include "common/command_registry.h"
#include "common/log_input_options.h"
#include "logs/log_files.h"
#include "workflow/log_inspection.h"

namespace driveid::cli {
namespace {

struct InspectOptions {
  std::vector<std::string> logs;
  LogInputCli input;
  double max_log_gib = 4.0;
  bool json = false;
  bool columns = false;
};

CLI::App* SetupInspect(CLI::App& app, InspectOptions& options) {
  CLI::App* command = app.add_subcommand(
      "inspect", "Show what the tools read from log files: columns, samples, rate, span, ranges, expressions, crops");
  command->add_option("logs", options.logs, "log files: CSV, MAT (v5, v7.3) or WPILib SysId JSON")->required();
  AddLogInputOptions(*command, options.input, "q=pi/180*#2");
  command->add_option("--max-log-size", options.max_log_gib, "largest log to read [GiB]")
      ->capture_default_str()
      ->check(FiniteWithin(1e-6, 1024.0));
  command->add_flag("--json", options.json, "print one JSON object");
  command->add_flag("--columns", options.columns,
                    "also list every column of a MAT file with its range (by default its variables and struct "
                    "fields, with their sizes and how to address them)");
  command->footer(
      "Examples:\n  " + app.get_name() + " inspect data/fig6_step.csv\n  " + app.get_name() +
      " inspect arm.csv --no-header --col t=#1 --col q=#2 --col tau=10*#14 --from 5");
  return command;
}

void RunInspect(const InspectOptions& options) {
  const ReadLimits limits = LogReadLimits(options.max_log_gib);
  LogInputOptions input = MakeLogInputOptions(options.input);
  input.selection.catalog = true;  // a WPILog lists its entries, routines and motors
  std::string text_out;
  Json json = Json::array();
  for (std::size_t i = 0; i < options.logs.size(); ++i) {
    const LogFileBytes file = ReadLogFile(options.logs[i], limits, false);
    const std::string& text = file.text;
    LogInputOptions file_input = input;
    file_input.selection.stream_file = file.stream_file;
    std::string join_text;
    std::vector<JoinedFile> joins;
    const std::string join_path = JoinFor(options.input, i, options.logs.size());
    if (!join_path.empty()) {
      join_text = ReadFileToString(join_path, limits);
      joins.push_back({join_path, &join_text, JoinTimingFor(options.input, i, options.logs.size())});
    }
    for (const auto& source : OpenLogSources(options.logs[i], text, joins, file_input)) {
      const InspectedLog inspected = InspectLog(*source, input, options.columns);
      if (options.json) json.push_back(LogInspectionJson(inspected));
      else text_out += FormatLogInspection(inspected);
    }
  }
  WriteStdout(options.json ? DumpJson(json) : text_out);
}

const bool kDrivetrain = RegisterCommand(Command<InspectOptions>(
    "drivetrain-fit", "", 5, [](CLI::App& parent, InspectOptions& o) { return SetupInspect(parent, o); },
    [](const InspectOptions& o, const std::string&) { RunInspect(o); }));
const bool kCDrive = RegisterCommand(Command<InspectOptions>(
    "cdrive-fit", "", 5, [](CLI::App& parent, InspectOptions& o) { return SetupInspect(parent, o); },
    [](const InspectOptions& o, const std::string&) { RunInspect(o); }));

}  // namespace
}  // namespace driveid::cli
