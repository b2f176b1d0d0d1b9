#include "logs/log_format.h"
#include "logs/log_input.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"
#include "logs/column_expression.h"
#include "logs/paired_source.h"

namespace driveid {

namespace {

std::vector<std::string> Alternatives(const std::string& entry) {
  std::vector<std::string> out;
  for (std::size_t start = entry.rfind('?', 0) == 0 ? 1 : 0;;) {
    const std::size_t bar = entry.find('|', start);
    out.push_back(entry.substr(start, bar == std::string::npos ? bar : bar - start));
    if (bar == std::string::npos) break;
    start = bar + 1;
  }
  return out;
}

bool IsPlainWord(const std::string& text) {
  for (const char* function : {"integral(", "derivative(", "detrend("}) {
    if (text.rfind(function, 0) == 0) return false;
  }
  // Products and sums are expressions; a name with a dash that the log has
  // is still taken whole (ParseColumnExpression checks it first).
  return text.find_first_of("*/+-") == std::string::npos;
}

// What the source offers, for messages: the first 12 column names.
std::string Offered(const TableSource& source) {
  const auto names = source.column_names();
  const bool unnamed = std::all_of(names.begin(), names.end(), [](const std::string& n) { return n.empty(); });
  if (unnamed) {
    return fmt::format("the file has no header: name its {} columns by position, e.g. ‹col› t=#1", names.size());
  }
  std::string have;
  for (std::size_t i = 0; i < names.size() && i < 12; ++i) {
    have += fmt::format("{}\"{}\"", i ? ", " : "", names[i].empty() ? fmt::format("#{}", i + 1) : names[i]);
  }
  if (names.size() > 12) have += fmt::format(", ... ({} columns)", names.size());
  return (source.format() == "csv" ? "header has " : "the file has ") + have;
}

std::string Where(const TableSource& source) {
  return source.segment().empty() ? source.path() : fmt::format("{} [{}]", source.path(), source.segment());
}

}  // namespace

namespace {

// Where each logical column comes from: an expression over a source column,
// a time base generated from --rate, or an optional column the log lacks.
struct ColumnPlan {
  std::vector<ColumnExpression> expressions;
  std::vector<std::size_t> indices;                   // the first term's source column
  std::vector<std::vector<std::size_t>> more_indices;  // the other terms' (a sum)
  std::vector<char> generated_time, absent;
};

// Every --col must name a column of this log format.
void CheckColumnOptions(const std::vector<std::string>& required, const LogInputOptions& options) {
  std::vector<std::string> known;
  for (const auto& entry : required) {
    for (const auto& name : Alternatives(entry)) known.push_back(name);
  }
  for (const auto& [name, expression] : options.columns) {
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      throw OptionError(fmt::format("‹col› {}={}: this log has no column '{}' (its columns: {})", name, expression,
                                    name, fmt::join(known, ", ")));
    }
  }
}

// The first alternative of each logical column the source has (or --col
// maps, or --rate generates); a missing one refused naming what the file
// offers; two logical columns reading one source column refused.
ColumnPlan PlanColumns(const TableSource& source, const std::vector<std::string>& required,
                       const LogInputOptions& options, const std::string& where, CsvLog& log) {
  ColumnPlan plan;
  plan.expressions.resize(required.size());
  plan.indices.resize(required.size());
  plan.generated_time.assign(required.size(), 0);
  plan.absent.assign(required.size(), 0);
  plan.more_indices.assign(required.size(), {});  // an optional column ("?name") the log does not have
  std::vector<ColumnExpression>& expressions = plan.expressions;
  std::vector<std::size_t>& indices = plan.indices;
  std::vector<char>& generated_time = plan.generated_time;
  std::vector<char>& absent = plan.absent;
  const auto is_column = [&](const std::string& word) { return source.Find(word).has_value(); };
  const auto scalar = [&](const std::string& word) { return source.scalar(word); };
  std::vector<std::string> missing;
  std::string first_missing;
  bool time_missing = false;
  for (std::size_t k = 0; k < required.size(); ++k) {
    const auto alternatives = Alternatives(required[k]);
    bool found = false;
    std::string wanted_all;
    for (const auto& name : alternatives) {
      const auto mapped = options.columns.find(name);
      std::string text = mapped != options.columns.end() ? mapped->second : source.DefaultReference(name);
      if (text.empty()) text = name;
      wanted_all += (wanted_all.empty() ? "'" : "' or '") + text;
      if (name == options.time_column && options.rate > 0.0) {
        if (mapped != options.columns.end()) {
          throw OptionError(fmt::format("‹rate› and ‹col› {}={}: give the time column or the rate, not both", name,
                                        mapped->second));
        }
        if (is_column(text)) {
          throw OptionError(fmt::format("‹rate›: {} has a time column '{}'; ‹rate› is for logs without one", where,
                                        text));
        }
        generated_time[k] = 1;
        log.names[k] = name;
        found = true;
        break;
      }
      if (mapped == options.columns.end() || IsPlainWord(text)) {
        if (!is_column(text)) continue;  // try the next alternative
      }
      expressions[k] = ParseColumnExpression(fmt::format("‹col› {}={}", name, text), text, is_column, scalar);
      indices[k] = *source.Find(expressions[k].reference);
      for (std::size_t t = 1; t < expressions[k].terms.size(); ++t) {
        plan.more_indices[k].push_back(*source.Find(expressions[k].terms[t].reference));
      }
      log.names[k] = name;
      found = true;
      break;
    }
    if (!found && required[k].rfind('?', 0) == 0) {
      absent[k] = 1;
      log.names[k] = alternatives.front();
      continue;
    }
    if (!found) {
      const bool time = alternatives.front() == options.time_column && options.time_column == "t";
      // A variable the reader skipped says why (complex, text, a cell ...).
      for (const auto& note : source.notes()) {
        for (const auto& name : alternatives) {
          const auto mapped = options.columns.find(name);
          const std::string text = mapped != options.columns.end() ? mapped->second : name;
          if (note.rfind(text + ": skipped", 0) == 0) throw InputError(fmt::format("{}: {}", where, note));
        }
      }
      // Every missing column is named in one message (a robot's log lacks
      // several at once); the mapping hint names the first.
      if (missing.empty()) {
        first_missing = alternatives.front();
        time_missing = time;
      }
      missing.push_back(wanted_all + "'");
    }
  }
  if (!missing.empty()) {
    throw InputError(fmt::format("{}{}: missing column{} {} ({}; map another name with ‹col› {}=COLUMN{})", where,
                                 source.header_line() > 0 ? fmt::format(":{}", source.header_line()) : "",
                                 missing.size() > 1 ? "s" : "", fmt::join(missing, ", "), Offered(source),
                                 first_missing, time_missing ? ", or give ‹rate› HZ" : ""));
  }
  // Two logical columns may not read one source column.
  for (std::size_t a = 0; a < required.size(); ++a) {
    for (std::size_t b = a + 1; b < required.size(); ++b) {
      // One column read twice is allowed when derived signals make them differ
      // (q_motor=integral(#2) with qd_motor=#2).
      const bool derived = (!expressions[a].operations.empty() || !expressions[b].operations.empty()) &&
                           expressions[a].operations != expressions[b].operations;
      if (!generated_time[a] && !generated_time[b] && !absent[a] && !absent[b] && indices[a] == indices[b] && !derived) {
        throw OptionError(fmt::format("‹col›: '{}' and '{}' would both read column '{}' of {}", log.names[a],
                                      log.names[b], expressions[a].reference, where));
      }
    }
  }
  return plan;
}

// The planned columns read (each source column once), scaled, with the
// generated time base; equal lengths required.
std::size_t ReadPlannedColumns(const TableSource& source, const std::vector<std::string>& required,
                               const LogInputOptions& options, const std::string& where, ColumnPlan& plan,
                               CsvLog& log) {
  const std::vector<ColumnExpression>& expressions = plan.expressions;
  const std::vector<std::size_t>& indices = plan.indices;
  const std::vector<char>& generated_time = plan.generated_time;
  const std::vector<char>& absent = plan.absent;
  // Each source column read once; `slot[k]` is logical column k's place in `data`.
  std::vector<std::size_t> to_read, slot(required.size(), 0);
  const auto slot_of = [&](std::size_t index) {
    const auto found = std::find(to_read.begin(), to_read.end(), index);
    if (found == to_read.end()) to_read.push_back(index);
    return static_cast<std::size_t>(std::find(to_read.begin(), to_read.end(), index) - to_read.begin());
  };
  std::vector<std::vector<std::size_t>> more_slots(required.size());
  for (std::size_t k = 0; k < required.size(); ++k) {
    if (generated_time[k] || absent[k]) continue;
    slot[k] = slot_of(indices[k]);
    for (std::size_t index : plan.more_indices[k]) more_slots[k].push_back(slot_of(index));
  }
  TableData data = source.Read(to_read);
  std::size_t rows = 0;
  bool first = true;
  std::string first_name;
  for (std::size_t k = 0; k < required.size(); ++k) {
    if (generated_time[k] || absent[k]) continue;
    const std::size_t n = data.columns[slot[k]].size();
    if (first) {
      rows = n;
      first_name = expressions[k].reference;
      first = false;
    } else if (n != rows) {
      throw InputError(fmt::format("{}: column '{}' has {} values but '{}' has {}: the columns of a log have one value "
                                   "per sample",
                                   where, expressions[k].reference, n, first_name, rows));
    }
  }
  if (first) {
    const auto lengths = source.column_lengths();
    rows = lengths.empty() ? 0 : lengths.front();
  }
  // A sum's further terms, taken before any source column is moved out.
  std::vector<std::vector<double>> more_sum(required.size());
  for (std::size_t k = 0; k < required.size(); ++k) {
    if (more_slots[k].empty()) continue;
    more_sum[k].assign(rows, 0.0);
    for (std::size_t t = 0; t < more_slots[k].size(); ++t) {
      const std::vector<double>& column = data.columns[more_slots[k][t]];
      if (column.size() != rows) {
        throw InputError(fmt::format("{}: column '{}' has {} values but '{}' has {}: the columns of a log have one "
                                     "value per sample",
                                     where, expressions[k].terms[t + 1].reference, column.size(), first_name, rows));
      }
      const double factor = expressions[k].terms[t + 1].factor;
      for (std::size_t i = 0; i < rows; ++i) more_sum[k][i] += factor * column[i];
    }
  }
  log.columns.resize(required.size());
  std::vector<int> uses(to_read.size(), 0);
  for (std::size_t k = 0; k < required.size(); ++k) {
    if (!generated_time[k] && !absent[k]) ++uses[slot[k]];
  }
  for (std::size_t k = 0; k < required.size(); ++k) {
    if (absent[k]) continue;  // left empty
    if (generated_time[k]) {
      log.columns[k].resize(rows);
      for (std::size_t i = 0; i < rows; ++i) log.columns[k][i] = static_cast<double>(i) / options.rate;
      log.notes.push_back(fmt::format("{}: samples at {} Hz from 0 s (‹rate›)", log.names[k], options.rate));
      continue;
    }
    // The last user of a source column takes it; earlier ones copy.
    if (--uses[slot[k]] == 0) {
      log.columns[k] = std::move(data.columns[slot[k]]);
    } else {
      log.columns[k] = data.columns[slot[k]];
    }
    const ColumnExpression& e = expressions[k];
    if (e.factor != 1.0 || !more_sum[k].empty() || e.offset != 0.0) {
      for (double& v : log.columns[k]) v = v * e.factor + e.offset;
      for (std::size_t i = 0; i < more_sum[k].size(); ++i) log.columns[k][i] += more_sum[k][i];
      for (std::size_t i = 0; i < rows; ++i) {
        if (!std::isfinite(log.columns[k][i])) {
          throw InputError(fmt::format("{}: ‹col› {}={}: the value at sample {} overflows", where, log.names[k], e.text,
                                       i + 1));
        }
      }
    }
    if (e.text != log.names[k]) log.notes.push_back(fmt::format("{} = {}", log.names[k], e.text));
  }
  log.line_numbers = std::move(data.line_numbers);
  return rows;
}

// Time strictly increasing, the crop (--from/--to), then the derived
// signals over the cropped time base.
void ApplyTimeBase(const std::vector<std::string>& required, const LogInputOptions& options, const std::string& where,
                   const ColumnPlan& plan, std::size_t rows, CsvLog& log) {
  const std::vector<ColumnExpression>& expressions = plan.expressions;
  const std::vector<char>& generated_time = plan.generated_time;
  const std::vector<char>& absent = plan.absent;
  const auto label = [&](std::size_t i) {
    return i < log.line_numbers.size() ? fmt::format("{}:{}", where, log.line_numbers[i])
                                       : fmt::format("{}: sample {}", where, i + 1);
  };
  for (std::size_t k = 0; k < required.size(); ++k) {
    if (log.names[k] != options.time_column) continue;
    if (!generated_time[k] && !absent[k] && !expressions[k].operations.empty()) {
      throw OptionError(fmt::format("‹col› {}={}: the time base cannot be derived (it is what derived signals are "
                                    "taken over); map a time column, or give ‹rate› HZ",
                                    log.names[k], expressions[k].text));
    }
    const auto& time = log.columns[k];
    for (std::size_t i = 1; i < time.size(); ++i) {
      if (!(time[i] > time[i - 1])) {
        throw InputError(fmt::format("{}: column '{}': {}not strictly increasing ({} after {})", label(i),
                                     options.time_column, options.time_column == "t" ? "time " : "", time[i],
                                     time[i - 1]));
      }
    }
    // Crop.
    if (options.from || options.to) {
      const double from = options.from.value_or(-INFINITY), to = options.to.value_or(INFINITY);
      std::size_t begin = 0, end = time.size();
      while (begin < end && time[begin] < from) ++begin;
      while (end > begin && time[end - 1] > to) --end;
      if (begin == end) {
        throw InputError(fmt::format("{}: no samples between ‹from› {} s and ‹to› {} s (the log spans {} .. {} s)",
                                     where, from, to, time.front(), time.back()));
      }
      for (auto& c : log.columns) {
        if (c.empty()) continue;  // an absent optional column
        c = std::vector<double>(c.begin() + static_cast<std::ptrdiff_t>(begin), c.begin() + static_cast<std::ptrdiff_t>(end));
      }
      if (!log.line_numbers.empty()) {
        log.line_numbers = std::vector<int>(log.line_numbers.begin() + static_cast<std::ptrdiff_t>(begin),
                                            log.line_numbers.begin() + static_cast<std::ptrdiff_t>(end));
      }
      log.notes.push_back(fmt::format("cropped to {} .. {} s (‹from›/‹to›): samples {} .. {} of {}",
                                      log.columns[k].front(), log.columns[k].back(), begin + 1, end, rows));
    }
    // Derived signals (integral, derivative, detrend) over the cropped time base.
    for (std::size_t j = 0; j < required.size(); ++j) {
      if (absent[j] || generated_time[j] || expressions[j].operations.empty()) continue;
      if (j == k) continue;  // refused above
      for (const auto& operation : expressions[j].operations) {
        ApplyColumnOperation(operation, log.columns[k], log.columns[j]);
      }
      for (double v : log.columns[j]) {
        if (!std::isfinite(v)) {
          throw InputError(fmt::format("{}: ‹col› {}={}: the derived signal overflows", where, log.names[j],
                                       expressions[j].text));
        }
      }
    }
    break;
  }
}

// Magnitudes a fit can square and sum: beyond 1e150 the sums of squares
// overflow, below 1e-150 they underflow (every estimate 0 +- 0).
void CheckMagnitudes(const std::vector<std::string>& required, const std::string& where, const CsvLog& log) {
  for (std::size_t k = 0; k < required.size(); ++k) {
    double largest = 0.0;
    for (double v : log.columns[k]) largest = std::max(largest, std::abs(v));
    if (largest > kLargestLogMagnitude || (largest > 0.0 && largest < kSmallestLogMagnitude)) {
      throw InputError(fmt::format("{}: column '{}': values up to {:.4g} in magnitude, outside {:g} .. {:g} where a "
                                   "fit's sums of squares stay finite; rescale it (‹col› {}=EXPR*FACTOR)",
                                   where, log.names[k], largest, kSmallestLogMagnitude, kLargestLogMagnitude,
                                   log.names[k]));
    }
  }
}

// The position's unit: the one given (‹unit›), else the log's. A ‹col› q
// that is not one of the log's columns as it stands (a scale, a sum, an
// offset) on a log that declares its unit is refused without ‹unit›: the
// numbers would change under the log's label (and a gain in V s/Meters would
// be per something else).
std::string PositionUnit(const TableSource& source, const std::vector<std::string>& required,
                         const LogInputOptions& options, const std::string& where) {
  const std::string declared = source.units();
  if (!options.position_unit.empty()) return options.position_unit;
  const auto q = options.columns.find("q");
  if (declared.empty() || q == options.columns.end() ||
      std::find(required.begin(), required.end(), "q") == required.end()) {
    return declared;
  }
  const auto names = source.column_names();
  if (std::find(names.begin(), names.end(), q->second) != names.end()) return declared;
  throw OptionError(fmt::format("{}: ‹col› q={} changes the position the log declares in '{}': name the unit of the "
                                "result with ‹unit› (e.g. ‹unit› Rotations; and scale qd alike)",
                                where, q->second, declared));
}

}  // namespace

CsvLog ReadLogColumns(const TableSource& source, const std::vector<std::string>& required,
                      const LogInputOptions& options) {
  RequireValid(options);
  const std::string where = Where(source);
  CheckColumnOptions(required, options);
  CsvLog log;
  log.path = source.path();
  log.segment = source.segment();
  log.format = source.format();
  log.units = PositionUnit(source, required, options, where);
  log.mechanism = source.mechanism();
  log.names = required;
  ColumnPlan plan = PlanColumns(source, required, options, where, log);
  const std::size_t rows = ReadPlannedColumns(source, required, options, where, plan, log);
  if (rows == 0) throw InputError(fmt::format("{}: no samples", where));
  ApplyTimeBase(required, options, where, plan, rows, log);
  CheckMagnitudes(required, where, log);
  log.comments = source.comments();
  const auto source_notes = source.notes();
  log.notes.insert(log.notes.begin(), source_notes.begin(), source_notes.end());
  return log;
}

std::vector<std::unique_ptr<TableSource>> OpenLogSources(const std::string& path, const std::string& text,
                                                         const std::vector<JoinedFile>& joins,
                                                         const LogInputOptions& options) {
  RequireValid(options);
  auto sources = OpenTableSources(path, text, options.csv, options.selection);
  for (const auto& join : joins) {
    auto joined = OpenTableSources(join.path, *join.text, options.csv, LogSelection{});
    if (joined.size() != 1 || sources.size() != 1) {
      throw OptionError(fmt::format("‹join› {}: only single-table files (CSV, MAT) can be joined", join.path));
    }
    if (!join.timing.time.empty()) {
      sources.front() = JoinSourcesByTime(std::move(sources.front()), std::move(joined.front()), join.timing, options);
      continue;
    }
    if (join.timing.shift || !join.timing.align.empty()) {
      throw OptionError(fmt::format("‹join› {}: a shift or an alignment joins by time: give the joined file's time "
                                    "column with ‹join-time›",
                                    join.path));
    }
    sources.front() = JoinSources(std::move(sources.front()), std::move(joined.front()));
  }
  return sources;
}

std::vector<CsvLog> ReadLogs(const std::string& path, const std::string& text, const std::vector<JoinedFile>& joins,
                             const std::vector<std::string>& required, const LogInputOptions& options) {
  RequireValid(options);
  std::vector<CsvLog> logs;
  for (const auto& source : OpenLogSources(path, text, joins, options)) logs.push_back(ReadLogColumns(*source, required, options));
  return logs;
}

CsvLog ParseCsvLog(const std::string& path, const std::string& text,
                   const std::vector<std::string>& required, const CsvReadOptions& options) {
  RequireValid(options);
  LogInputOptions input;
  input.columns = options.column_map;
  input.time_column = options.time_column;
  input.csv.max_line_bytes = options.max_line_bytes;
  std::vector<CsvLog> logs = ReadLogs(path, text, {}, required, input);
  if (logs.size() != 1) {
    throw InputError(fmt::format("{}: {} logs in one file (a SysId file): this reader takes one", path, logs.size()));
  }
  return std::move(logs.front());
}

CsvLog ReadCsvLog(const std::string& path, const std::vector<std::string>& required,
                  const CsvReadOptions& options) {
  return ParseCsvLog(path, ReadFileToString(path), required, options);
}

}  // namespace driveid
