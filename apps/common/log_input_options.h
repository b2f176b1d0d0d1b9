// The options of every subcommand that reads logs (docs/formats.md#logs):
// --col NAME=EXPR, --no-header, --delimiter, --rate, --from, --to, --join
// (row by row or by time: --join-time, --join-shift, --join-align), --side, and reading the logs with their provenance.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "common/cli_support.h"
#include "io/csv_log.h"
#include "io/log_input.h"
#include "io/sha256.h"
#include "io/transpose_table.h"

namespace driveid::cli {

struct LogInputCli {
  std::vector<std::string> columns;  ///< --col NAME=EXPR
  bool no_header = false;
  std::string delimiter;             ///< "", "comma", "semicolon", "tab", "space" (or the character)
  double rate = 0.0;
  double from = -INFINITY, to = INFINITY;
  std::vector<std::string> join;
  std::string join_time;                ///< --join-time EXPR: join by time
  std::vector<double> join_shift;       ///< --join-shift S: once, or once per log
  std::string join_align;               ///< --join-align A=B
  std::string side;
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

/// Reads each log once (at most --max-log-size bytes; joined files too),
/// makes its logs with `make(CsvLog)` (a SysId file gives several) and
/// records each one's provenance (file, SHA-256, samples, segment, notes).
/// Refuses (exit 2) a file whose contents were given already. The column
/// `time_column` must increase strictly (a frequency for a measured response).
/// `transpose`: the files hold one signal per row (io/transpose_table.h).
template <typename Log, typename Make>
std::vector<Log> LoadLogs(const std::vector<std::string>& paths, const LogInputCli& input,
                          const FitOutputOptions& output, FitProvenance& provenance,
                          const std::vector<std::string>& columns, Make make, const std::string& time_column = "t",
                          bool transpose = false) {
  ReadLimits limits;
  limits.lines_unless_structured = true;  // logs may be JSON or MAT
  limits.max_bytes = static_cast<std::size_t>(output.max_log_gib * 1073741824.0);
  limits.max_bytes_hint = fmt::format("a log may be at most {} GiB (raise with --max-log-size)", output.max_log_gib);
  LogInputOptions options = MakeLogInputOptions(input);
  options.time_column = time_column;
  std::vector<Log> logs;
  std::vector<std::pair<std::string, std::string>> seen;  // hash, file
  for (std::size_t i = 0; i < paths.size(); ++i) {
    const std::string& path = paths[i];
    const std::string raw = ReadFileToString(path, limits);
    const std::string hash = Sha256Hex(raw);
    const std::string text = transpose ? TransposeTable(path, raw) : raw;
    // The same data twice would count twice and shrink every std by sqrt(2).
    for (const auto& [earlier_hash, earlier] : seen) {
      if (earlier_hash == hash) {
        throw OptionError(fmt::format("{}: the same data as {} (sha256 {}): give each log once", path, earlier,
                                      hash.substr(0, 12)));
      }
    }
    seen.emplace_back(hash, path);
    std::vector<std::string> join_notes;
    std::string join_text;
    std::vector<JoinedFile> joins;
    const std::string join_path = JoinFor(input, i, paths.size());
    if (!join_path.empty()) {
      join_text = ReadFileToString(join_path, limits);
      joins.push_back({join_path, &join_text, JoinTimingFor(input, i, paths.size())});
      join_notes.push_back(fmt::format("joined with {} (sha256 {})", join_path, Sha256Hex(join_text)));
    }
    for (CsvLog& csv : ReadLogs(path, text, joins, columns, options)) {
      DataFileRecord record{path, hash, static_cast<int>(csv.rows()), csv.segment, csv.notes};
      record.notes.insert(record.notes.end(), join_notes.begin(), join_notes.end());
      logs.push_back(make(std::move(csv)));
      provenance.data.push_back(std::move(record));
    }
  }
  return logs;
}

}  // namespace driveid::cli
