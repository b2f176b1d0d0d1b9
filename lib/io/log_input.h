// One input layer for every log (docs/formats.md#logs): a file (CSV, MAT,
// SysId JSON; plus files joined row by row) becomes one or more logs with
// the logical columns a model needs. Logical columns are mapped with
// `--col NAME=EXPR` (column expressions), time comes from a column or from
// `--rate`, and `--from/--to` crop each log. Everything applied is recorded
// in the log's notes for the provenance.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/csv_log.h"
#include "io/table_source.h"
#include "io/time_join.h"

namespace driveid {

/// A log column whose largest magnitude exceeds this (or is below the
/// smallest, other than all zeros) is refused: a fit could not square it.
inline constexpr double kLargestLogMagnitude = 1e150;
inline constexpr double kSmallestLogMagnitude = 1e-150;

struct LogInputOptions {
  /// Logical column name -> expression (`--col NAME=EXPR`).
  std::map<std::string, std::string> columns;
  CsvFormat csv;
  SysIdFormat sysid;
  double rate = 0.0;  ///< --rate [Hz]: samples at this rate from t = 0 (0: the time column)
  std::optional<double> from, to;  ///< --from, --to [s]: crop in the log's time
  std::string time_column = "t";   ///< strictly increasing
  /// Every bound on these fields (‹field› names the option); see core/option_check.h.
  bool IsValid(std::string* error) const;
};

/// A file joined (`--join`): its name and contents, row by row or by time.
struct JoinedFile {
  std::string path;
  const std::string* text = nullptr;
  JoinTiming timing;
};

/// Reads the logs of one file. `required` lists logical names; "a|b" takes
/// a, or b when a is neither mapped nor present; "?a" is optional (left
/// empty when neither mapped nor present). Throws InputError naming
/// the file and line (or variable), OptionError for a bad --col.
std::vector<CsvLog> ReadLogs(const std::string& path, const std::string& text, const std::vector<JoinedFile>& joins,
                             const std::vector<std::string>& required, const LogInputOptions& options);

/// The sources of one file with its joined files (a SysId file has several;
/// only a single-table file can be joined: OptionError otherwise).
std::vector<std::unique_ptr<TableSource>> OpenLogSources(const std::string& path, const std::string& text,
                                                         const std::vector<JoinedFile>& joins,
                                                         const LogInputOptions& options);

/// The same for sources already open (one log per source).
CsvLog ReadLogColumns(const TableSource& source, const std::vector<std::string>& required,
                      const LogInputOptions& options);

}  // namespace driveid
