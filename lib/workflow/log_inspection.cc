#include "workflow/log_inspection.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/order_statistics.h"
#include "logs/log_format.h"

namespace driveid {
namespace {

void Range(const std::vector<double>& values, InspectedColumn& column) {
  column.length = values.size();
  if (values.empty()) return;
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  column.min = *lo;
  column.max = *hi;
}

}  // namespace

InspectedLog InspectLog(const TableSource& source, const LogInputOptions& options, bool list_columns) {
  InspectedLog out;
  out.path = source.path();
  out.segment = source.segment();
  out.format = source.format();
  out.notes = source.notes();
  out.variables = source.variables();
  const auto names = out.variables.empty() || list_columns ? source.column_names() : std::vector<std::string>{};
  std::vector<std::size_t> all(names.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  // All at once; a column that is not numbers is read alone to say so.
  std::vector<std::vector<double>> values;
  std::vector<std::string> problems(names.size());
  try {
    values = source.Read(all).columns;
  } catch (const InputError&) {
    values.assign(names.size(), {});
    for (std::size_t i = 0; i < names.size(); ++i) {
      try {
        values[i] = std::move(source.Read({i}).columns.front());
      } catch (const InputError& e) {
        problems[i] = e.what();
      }
    }
  }
  for (std::size_t i = 0; i < names.size(); ++i) {
    InspectedColumn column;
    column.name = names[i].empty() ? fmt::format("#{}", i + 1) : names[i];
    column.position = i + 1;
    column.problem = problems[i];
    Range(values[i], column);
    out.columns.push_back(column);
    std::vector<double>().swap(values[i]);  // a long log's copy is not held while the fit's view is read
  }
  const std::vector<std::size_t> lengths = source.column_lengths();
  out.rows = lengths.empty() ? 0 : *std::max_element(lengths.begin(), lengths.end());
  // A catalog (a WPILog's entries) has no columns of its own: its tests
  // follow as their own sources.
  if (names.empty() && !out.variables.empty() && source.column_lengths().empty()) return out;
  // The time base and the mapped columns, as a fit would read them.
  std::vector<std::string> wanted = {options.time_column};
  for (const auto& [name, expression] : options.columns) {
    if (name != options.time_column) wanted.push_back(name);
  }
  try {
    const CsvLog log = ReadLogColumns(source, wanted, options);
    const auto& time = log.columns.front();
    out.has_time = true;
    out.start = time.front();
    out.end = time.back();
    out.rows = time.size();
    if (time.size() >= 2) {
      std::vector<double> steps(time.size() - 1);
      for (std::size_t k = 1; k < time.size(); ++k) steps[k - 1] = time[k] - time[k - 1];
      const double median = Median(steps);
      const auto [lo, hi] = std::minmax_element(steps.begin(), steps.end());
      out.rate = 1.0 / median;
      out.jitter = (*hi - *lo) / median;
    }
    for (std::size_t k = 0; k < log.names.size(); ++k) {
      InspectedColumn column;
      column.name = log.names[k];
      const auto mapped = options.columns.find(log.names[k]);
      column.source = mapped != options.columns.end() ? mapped->second : "";
      Range(log.columns[k], column);
      out.mapped.push_back(column);
    }
    out.notes = log.notes;
  } catch (const std::exception& e) {
    out.time_problem = e.what();
  }
  return out;
}

namespace {

// A time for the listing: to the microsecond where it is large (a bag's
// seconds since 1970, which {:.6g} showed as "1.70591e+09 .. 1.70591e+09"),
// else in 6 significant digits.
std::string TimeText(double t) {
  return std::abs(t) >= 1e5 ? fmt::format("{:.6f}", t) : fmt::format("{:.6g}", t);
}

}  // namespace

std::string FormatLogInspection(const InspectedLog& log) {
  std::string out = fmt::format("{}{} ({})\n", log.path, log.segment.empty() ? "" : " [" + log.segment + "]", log.format);
  // What the format says of its catalog (a WPILog's entries, a bag's topics) or variables (logs/log_format.h).
  const LogFormat* format = FindLogFormatOfSource(log.format);
  const LogFormatCatalog listing = format != nullptr ? format->catalog : LogFormatCatalog{};
  const bool catalog = !listing.summary.empty() && log.segment.empty();
  if (log.has_time) {
    out += fmt::format("  {} samples, t = {} .. {} s ({:.6g} s), rate {:.6g} Hz, jitter {:.3g} % of the step\n",
                       log.rows, TimeText(log.start), TimeText(log.end), log.end - log.start, log.rate, 100.0 * log.jitter);
  } else if (catalog) {
    out += "  " + listing.summary + "\n";
  } else {
    out += fmt::format("  {} rows; not readable as a fit would read it: {}\n", log.rows, log.time_problem);
  }
  for (const auto& note : log.notes) out += "  note: " + note + "\n";
  if (!log.variables.empty()) {
    std::size_t width = 8;
    for (const auto& v : log.variables) width = std::max(width, std::min<std::size_t>(v.name.size(), 48));
    const LogFormatCatalog heading = catalog ? listing : LogFormatCatalog{};
    out += fmt::format("  {:<{}} {:>13}  {}\n", heading.item, width, heading.count, heading.description);
    for (const auto& v : log.variables) {
      out += fmt::format("  {:<{}} {:>13}  {}\n", v.name, width, fmt::format("{} x {}", v.rows, v.cols), v.address);
    }
    if (log.columns.empty() && !catalog) out += "  (columns with their ranges: inspect ‹columns›)\n";
  }
  if (!log.columns.empty()) {
    out += fmt::format("  {:>5}  {:<28} {:>8} {:>14} {:>14}\n", "#", "column", "values", "min", "max");
  }
  for (const auto& c : log.columns) {
    if (!c.problem.empty()) {
      out += fmt::format("  {:>5}  {:<28} {}\n", c.position, c.name, c.problem);
    } else {
      out += fmt::format("  {:>5}  {:<28} {:>8} {:>14.6g} {:>14.6g}\n", c.position, c.name, c.length, c.min, c.max);
    }
  }
  if (!log.mapped.empty()) {
    out += "  as a fit reads it:\n";
    for (const auto& c : log.mapped) {
      out += fmt::format("  {:>5}  {:<28} {:>8} {:>14.6g} {:>14.6g}\n", "", c.source.empty() ? c.name : c.name + " = " + c.source,
                         c.length, c.min, c.max);
    }
  }
  return out;
}

Json LogInspectionJson(const InspectedLog& log) {
  Json out = {{"file", log.path}, {"segment", log.segment}, {"format", log.format}, {"samples", log.rows}};
  if (log.has_time) {
    out["time"] = {{"start", log.start}, {"end", log.end}, {"rate", log.rate}, {"jitter", log.jitter}};
  } else {
    out["time"] = nullptr;
    out["time_problem"] = log.time_problem;
  }
  out["notes"] = log.notes;
  out["variables"] = Json::array();
  for (const auto& v : log.variables) {
    out["variables"].push_back({{"name", v.name}, {"rows", v.rows}, {"cols", v.cols}, {"address", v.address}});
  }
  out["columns"] = Json::array();
  for (const auto& c : log.columns) {
    Json column = {{"position", c.position}, {"name", c.name}, {"values", c.length}};
    if (c.problem.empty()) {
      column["min"] = c.min;
      column["max"] = c.max;
    } else {
      column["problem"] = c.problem;
    }
    out["columns"].push_back(column);
  }
  out["mapped"] = Json::array();
  for (const auto& c : log.mapped) {
    out["mapped"].push_back({{"name", c.name}, {"expression", c.source}, {"values", c.length}, {"min", c.min}, {"max", c.max}});
  }
  return out;
}

}  // namespace driveid
