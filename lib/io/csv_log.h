// Reader for the log files of docs/formats.md#logs: UTF-8 text, comma separated,
// one header row, '#' comment lines, SI units. Parsing is strict: every
// problem throws InputError "file:line: column 'name': what".
#pragma once

#include <map>
#include <utility>
#include <string>
#include <vector>

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

/// Parses a log already in memory (CSV, or any format of ReadLogs that
/// holds one log). `path` is used in messages only. `required` lists the
/// logical names that must be present; an entry "a|b" accepts column a or,
/// if absent, column b (log.names tells which). Every row must have exactly
/// as many fields as the header, and the requested fields must be finite.
CsvLog ParseCsvLog(const std::string& path, const std::string& text,
                   const std::vector<std::string>& required, const CsvReadOptions& options = {});

/// Reads and parses a file (see ParseCsvLog). Throws InputError if unreadable.
CsvLog ReadCsvLog(const std::string& path, const std::vector<std::string>& required,
                  const CsvReadOptions& options = {});

/// A writer's check: throws OutputError (exit 3) naming a column whose length
/// is not the times', else the column and time of the first non-finite
/// value, which the tools' own reader would refuse. `columns` pairs a column
/// name with its values; `time` gives the sample times.
void RequireFiniteColumns(const std::vector<std::pair<std::string, const std::vector<double>*>>& columns,
                          const std::vector<double>& time);

/// Limits enforced while a file is read (an endless input fails fast).
struct ReadLimits {
  std::size_t max_bytes = std::size_t{4} << 30;  ///< whole file (default 4 GiB)
  std::size_t max_line_bytes = 1 << 20;         ///< one line; 0 = no limit (binary files)
  /// Drop the line limit when the file starts as JSON ('{'), MAT or HDF5
  /// (files of logs; the whole-file limit still holds).
  bool lines_unless_structured = false;
  std::string max_bytes_hint = "a log may be at most 4 GiB";  ///< how to raise max_bytes, for the message
  double fifo_wait_seconds = 5.0;  ///< a named FIFO's writer must send its first bytes within this
};

/// Reads a whole file into memory; throws InputError naming the file (and
/// the line) when it cannot be read, is a directory or exceeds `limits`
/// (a regular file by its size, before reading), when a line-oriented file
/// holds a control byte (binary data: refused at its first chunk), when a
/// named FIFO gets no writer in time, or when it does not fit in memory.
std::string ReadFileToString(const std::string& path, const ReadLimits& limits = {});

/// Parses `--col NAME=HEADER` entries; throws InputError on a malformed entry.
std::map<std::string, std::string> ParseColumnMap(const std::vector<std::string>& entries);

}  // namespace driveid
