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

#include "logs/csv_log.h"
#include "logs/log_options.h"
#include "logs/table_source.h"
#include "logs/time_join.h"

namespace driveid {

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

}  // namespace driveid
