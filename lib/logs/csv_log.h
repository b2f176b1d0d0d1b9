// A log as the models read it (docs/formats.md#logs): the logical columns a
// model asked for, in SI units, with the file, part and notes they came from
// (logs/log_input.h reads them from any format; every problem throws
// InputError "file:line: column 'name': what").
#pragma once

#include <map>
#include <utility>
#include <string>
#include <vector>

#include "system/file_reading.h"

namespace driveid {

/// A parsed log: the requested columns, in the order they were requested,
/// stored column-major. Names are the logical names (after --col mapping).
struct CsvLog {
  std::string path;                        ///< file the data came from (for messages)
  std::string segment;                     ///< part of the file ("slow-forward/left"), "" for all of it
  std::string format = "csv";              ///< "csv", "mat" or "sysid"
  std::string units;                       ///< position unit the file declares (SysId `units`), "" if none
  std::string mechanism;                   ///< mechanism the file declares (SysId `test`), "" if none
  std::vector<std::string> names;          ///< logical column names, as requested
  std::vector<std::vector<double>> columns;  ///< columns[k][row], SI units
  std::vector<int> line_numbers;           ///< 1-based file line of each row (empty for MAT and JSON)
  std::vector<std::string> comments;       ///< comment lines and the reader's notes on the source
  std::vector<std::string> notes;          ///< expressions, --rate, crops applied (for the provenance)

  std::size_t rows() const { return columns.empty() ? 0 : columns.front().size(); }
  /// The log's name in messages and fits: the path, with " [segment]" for part of a file.
  std::string label() const { return segment.empty() ? path : path + " [" + segment + "]"; }
  /// Column by logical name; throws std::out_of_range for a name not requested.
  const std::vector<double>& column(const std::string& name) const;
};

/// Options of the reader.
struct CsvReadOptions {
  /// Logical column name -> header text in the file (from `--col NAME=HEADER`).
  std::map<std::string, std::string> column_map;
  /// Name of the time column, which must be strictly increasing ("" = none).
  std::string time_column = "t";
  /// Longest accepted line, in bytes (a longer one is an error, not a hang).
  std::size_t max_line_bytes = 1 << 20;
  /// Every bound on these fields (‹field› names the option); see core/option_check.h.
  bool IsValid(std::string* error) const;
};

/// A writer's check: throws OutputError (exit 3) naming a column whose length
/// is not the times', else the column and time of the first non-finite
/// value, which the tools' own reader would refuse. `columns` pairs a column
/// name with its values; `time` gives the sample times.
void RequireFiniteColumns(const std::vector<std::pair<std::string, const std::vector<double>*>>& columns,
                          const std::vector<double>& time);

/// Parses `--col NAME=HEADER` entries; throws InputError on a malformed entry.
std::map<std::string, std::string> ParseColumnMap(const std::vector<std::string>& entries);

}  // namespace driveid
