// A log type's columns, declared once (as the parameter tables declare
// parameters): from one table follow the columns the reader asks for, the
// log made from what it read, and the CSV the tools write
// (logs/step_log.h, logs/axis_log.h, logs/joint_log.h, logs/robot_log.h,
// logs/cdrive_log.h; docs/formats.md#logs).
#pragma once

#include <cstddef>
#include <iterator>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "logs/log_input.h"

namespace driveid {

template <typename Log>
struct LogColumn {
  /// Logical name; "a|b" reads column a, or else b (CsvLog::names says which).
  std::string_view name;
  /// May be absent from a log (its vector then stays empty).
  bool optional = false;
  /// The log's vector that holds the column; nullptr: read for the log's
  /// maker, which takes it from the CsvLog first (not stored as read).
  std::vector<double>& (*field)(Log&) = nullptr;
  /// The column's format when the tools write this log (under the first
  /// name of `name`); empty: not written.
  std::string_view write = {};
};

template <typename Log>
using ColumnField = std::vector<double>& (*)(Log&);

/// The accessor of a vector member, for table rows.
template <typename Log, std::vector<double> Log::*Member>
std::vector<double>& FieldOf(Log& log) {
  return log.*Member;
}

/// A column every log must have; `write` as LogColumn::write.
template <typename Log>
constexpr LogColumn<Log> RequiredColumn(std::string_view name, ColumnField<Log> field, std::string_view write = {}) {
  return {name, false, field, write};
}
/// A column a log may lack (never written).
template <typename Log>
constexpr LogColumn<Log> OptionalColumn(std::string_view name, ColumnField<Log> field) {
  return {name, true, field, {}};
}

/// Index of the column named `name` (exactly as in the table), for
/// static_assert'ed constants; the table's size if none.
template <typename Log, std::size_t N>
constexpr std::size_t LogColumnIndex(const LogColumn<Log> (&table)[N], std::string_view name) {
  for (std::size_t k = 0; k < N; ++k) {
    if (table[k].name == name) return k;
  }
  return N;
}

/// The columns ReadLogs / ParseCsvLog ask for: the names, optional ones
/// prefixed with '?'.
template <typename Log, std::size_t N>
std::vector<std::string> LogColumnRequest(const LogColumn<Log> (&table)[N]) {
  std::vector<std::string> names;
  for (const auto& column : table) names.push_back((column.optional ? "?" : "") + std::string(column.name));
  return names;
}

/// The log from the columns read in table order (moved out of `csv`); its
/// `path` from the log's label.
template <typename Log, std::size_t N>
Log MakeLogFromColumns(const LogColumn<Log> (&table)[N], CsvLog& csv) {
  Log log;
  log.path = csv.label();
  for (std::size_t k = 0; k < N && k < csv.columns.size(); ++k) {
    if (table[k].field) table[k].field(log) = std::move(csv.columns[k]);
  }
  return log;
}

/// CSV text of the written columns, '#' comment lines first; throws
/// OutputError for a value the reader would refuse or a column whose length
/// is not the time column's.
template <typename Log, std::size_t N>
std::string FormatLogColumns(const LogColumn<Log> (&table)[N], const Log& log,
                             const std::vector<std::string>& comments) {
  Log& readable = const_cast<Log&>(log);  // (the accessors are shared with MakeLogFromColumns; nothing is changed)
  std::vector<std::pair<std::string, const std::vector<double>*>> written;
  std::vector<std::string_view> formats;
  for (const auto& column : table) {
    if (column.write.empty() || !column.field) continue;
    written.emplace_back(std::string(column.name.substr(0, column.name.find('|'))), &column.field(readable));
    formats.push_back(column.write);
  }
  const std::vector<double>& time = *written.front().second;
  RequireFiniteColumns(written, time);
  std::string out;
  for (const auto& line : comments) out += "# " + line + "\n";
  for (std::size_t c = 0; c < written.size(); ++c) out += (c > 0 ? "," : "") + written[c].first;
  out += "\n";
  auto sink = std::back_inserter(out);
  for (std::size_t k = 0; k < time.size(); ++k) {
    for (std::size_t c = 0; c < written.size(); ++c) {
      if (c > 0) out += ',';
      fmt::format_to(sink, fmt::runtime(formats[c]), (*written[c].second)[k]);
    }
    out += '\n';
  }
  return out;
}

}  // namespace driveid
