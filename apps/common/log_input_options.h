// The options of every subcommand that reads logs (docs/formats.md#logs):
// --col NAME=EXPR, --no-header, --skip-rows, --delimiter, --rate, --from, --to, --join
// (row by row or by time: --join-time, --join-shift, --join-align), --side, and reading the logs with their provenance.
#pragma once

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "common/cli_support.h"
#include "logs/csv_log.h"
#include "logs/log_files.h"
#include "logs/log_input.h"

namespace driveid::cli {

struct LogInputCli {
  std::vector<std::string> columns;  ///< --col NAME=EXPR
  bool no_header = false;
  int skip_rows = 0;                 ///< --skip-rows N: lines before the header
  std::string delimiter;             ///< "", "comma", "semicolon", "tab", "space" (or the character)
  double rate = 0.0;
  double from = -INFINITY, to = INFINITY;
  std::vector<std::string> join;
  std::string join_time;                ///< --join-time EXPR: join by time
  std::vector<double> join_shift;       ///< --join-shift S: once, or once per log
  std::string join_align;               ///< --join-align A=B
  /// --side (SysId JSON); --mechanism, --motor, --test (WPILog); --topic,
  /// --joint (repeated), --time, --joint-motor, --joint-link (ROS bags),
  /// bound to the readers' own options as they are (logs/log_selection.h).
  /// bag.every_joint is not a flag: a serial robot's command reads every
  /// joint of a bag by default.
  LogSelection selection;
  std::string unit;                  ///< --unit: the position's unit
  std::vector<std::string> entries;  ///< --entry ROLE=NAME (WPILog), into selection.wpilog.entries
};

/// Every input file of a command reading logs: the logs, the parameter file,
/// the --join files and `more` (e.g. --validate logs), for CheckFitOutputs.
std::vector<std::string> LogCommandInputs(const std::vector<std::string>& logs, const std::string& params,
                                          const LogInputCli& input, const std::vector<std::string>& more = {});

/// Adds the options; `example` shows a --col for this log kind.
void AddLogInputOptions(CLI::App& command, LogInputCli& options, const std::string& example);

/// The library's options from the command line's; OptionError for a bad value.
LogInputOptions MakeLogInputOptions(const LogInputCli& options);

/// The --join file for the k-th of `count` logs ("" for none): one --join
/// for one log, or one per log; OptionError otherwise.
std::string JoinFor(const LogInputCli& options, std::size_t k, std::size_t count);

/// How the k-th of `count` logs meets its joined file (--join-time,
/// --join-shift once or once per log, --join-align); OptionError otherwise.
JoinTiming JoinTimingFor(const LogInputCli& options, std::size_t k, std::size_t count);

/// Each log with its --join file and timing (JoinFor, JoinTimingFor).
std::vector<LogFileRequest> LogFileRequests(const LogInputCli& options, const std::vector<std::string>& paths);

/// The read limits of a log: --max-log-size [GiB] for the file (and its
/// joined file), no line limit for JSON, MAT and HDF5 files.
ReadLimits LogReadLimits(double max_log_gib);

/// Prints on stderr the readers' warnings (logs/table_source.h kReaderWarning)
/// in records[first..], each once, naming its file.
void ShowReaderWarnings(const std::vector<DataFileRecord>& records, std::size_t first);

/// A log in memory (the Python module's arrays, docs/python.md), read under
/// `name` as a file with these columns would be: --col, --from, --to and
/// --rate apply, and its record holds the SHA-256 of its values.
struct GivenLog {
  std::string name;
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;
};

/// While it lives, this thread's LoadLogs reads a log path equal to a given
/// log's name from memory instead of from a file.
class GivenLogsScope {
 public:
  explicit GivenLogsScope(const std::vector<GivenLog>& logs);
  ~GivenLogsScope();
  GivenLogsScope(const GivenLogsScope&) = delete;
  GivenLogsScope& operator=(const GivenLogsScope&) = delete;

 private:
  const std::vector<GivenLog>* previous_;
};

/// Whether a GivenLogsScope is alive on this thread.
bool HasGivenLogs();

/// Reads the given log named `path` with `columns` (as ReadLogColumns),
/// appends its record and hands it to `take`; false when none has that name.
bool ReadGivenLog(const std::string& path, const std::vector<std::string>& columns, const LogInputOptions& options,
                  std::vector<DataFileRecord>& records, const std::function<void(CsvLog)>& take);

/// Reads each log once (at most --max-log-size bytes; joined files too),
/// makes its logs with `make(CsvLog)` (a SysId file gives several) and
/// records each one's provenance (file, SHA-256, samples, segment, notes).
/// Refuses (exit 2) a file whose contents were given already. The column
/// `time_column` must increase strictly (a frequency for a measured response).
/// `transpose`: the files hold one signal per row (logs/transpose_table.h).
/// The reading is logs/log_files.h ReadLogFiles'.
template <typename Log, typename Make>
std::vector<Log> LoadLogs(const std::vector<std::string>& paths, const LogInputCli& input,
                          const FitOutputOptions& output, FitProvenance& provenance,
                          const std::vector<std::string>& columns, Make make, const std::string& time_column = "t",
                          bool transpose = false) {
  LogInputOptions options = MakeLogInputOptions(input);
  options.time_column = time_column;
  std::vector<Log> logs;
  const std::size_t first_record = provenance.data.size();
  const std::function<void(CsvLog)> take = [&](CsvLog csv) { logs.push_back(make(std::move(csv))); };
  const auto read = [&](const std::vector<std::string>& files) {
    ReadLogFiles(LogFileRequests(input, files), columns, options, LogReadLimits(output.max_log_gib), transpose,
                 provenance.data, take);
  };
  if (!HasGivenLogs()) {
    read(paths);
  } else {
    if (!input.join.empty()) throw OptionError("--join joins files: not with logs given as arrays");
    for (const std::string& path : paths) {
      if (!ReadGivenLog(path, columns, options, provenance.data, take)) read({path});
    }
  }
  ShowReaderWarnings(provenance.data, first_record);
  return logs;
}

}  // namespace driveid::cli
