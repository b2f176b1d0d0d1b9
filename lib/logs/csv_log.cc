#include "logs/csv_log.h"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"
#include "system/file_reading.h"

namespace driveid {

bool CsvReadOptions::IsValid(std::string* error) const {
  OptionCheck check(error);
  for (const auto& [name, header] : column_map) {
    check.Require(!name.empty() && !header.empty(), fmt::format("‹col› '{}={}': a name and a header", name, header));
  }
  return check;
}

const std::vector<double>& CsvLog::column(const std::string& name) const {
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (names[k] == name) return columns[k];
  }
  throw std::out_of_range("CsvLog::column: no column '" + name + "'");
}

void RequireFiniteColumns(const std::vector<std::pair<std::string, const std::vector<double>*>>& columns,
                          const std::vector<double>& time) {
  for (const auto& [name, values] : columns) {
    if (values->size() != time.size()) {
      throw OutputError(fmt::format("column '{}' holds {} values for {} times; nothing written", name, values->size(),
                                    time.size()));
    }
  }
  for (const auto& [name, values] : columns) {
    for (std::size_t k = 0; k < values->size(); ++k) {
      if (!std::isfinite((*values)[k])) {
        throw OutputError(fmt::format(
            "column '{}' would be {} at t = {} s (sample {}): the parameters or options overflow the simulation; "
            "nothing written",
            name, (*values)[k], k < time.size() ? time[k] : 0.0, k + 1));
      }
    }
  }
}

std::map<std::string, std::string> ParseColumnMap(const std::vector<std::string>& entries) {
  std::map<std::string, std::string> map;
  for (const auto& entry : entries) {
    const auto eq = entry.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == entry.size()) {
      throw InputError(fmt::format("‹col› {}: expected NAME=HEADER", entry));
    }
    map[entry.substr(0, eq)] = entry.substr(eq + 1);
  }
  return map;
}

}  // namespace driveid
