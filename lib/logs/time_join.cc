#include "logs/time_join.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"
#include "logs/column_expression.h"
#include "logs/log_options.h"
#include "logs/paired_source.h"
#include "signal/clock_alignment.h"
#include "signal/resample.h"

namespace driveid {
namespace {

struct Series {
  std::vector<double> values;
  std::vector<int> lines;
};

// One column expression of `source` (a column times constants; no derived
// signals), read and scaled.
Series ReadExpression(const TableSource& source, const std::string& option, const std::string& text) {
  const auto is_column = [&](const std::string& word) { return source.Find(word).has_value(); };
  const auto scalar = [&](const std::string& word) { return source.scalar(word); };
  const ColumnExpression e = ParseColumnExpression(option, text, is_column, scalar);
  if (!e.operations.empty()) {
    throw OptionError(fmt::format("{}: derived signals ({}) cannot time or align a join", option, e.operations.front()));
  }
  if (e.terms.size() > 1) {
    throw OptionError(fmt::format("{}: a join's time or alignment is one scaled column (with a constant), not a sum of "
                                  "columns", option));
  }
  const auto index = source.Find(e.reference);
  if (!index) throw OptionError(fmt::format("{}: {} has no column '{}'", option, source.path(), e.reference));
  TableData data = source.Read({*index});
  Series out{std::move(data.columns.front()), std::move(data.line_numbers)};
  for (double& v : out.values) v = v * e.factor + e.offset;
  return out;
}

void CheckIncreasing(const TableSource& source, const Series& time, const std::string& what) {
  for (std::size_t i = 1; i < time.values.size(); ++i) {
    if (!(time.values[i] > time.values[i - 1])) {
      const std::string where = i < time.lines.size() ? fmt::format("{}:{}", source.path(), time.lines[i])
                                                      : fmt::format("{}: sample {}", source.path(), i + 1);
      throw InputError(fmt::format("{}: {} not strictly increasing ({} after {}): a file joined by time needs both "
                                   "time bases increasing",
                                   where, what, time.values[i], time.values[i - 1]));
    }
  }
  if (time.values.size() < 2) throw InputError(fmt::format("{}: {} has fewer than 2 samples", source.path(), what));
}

// The log's time: its time column as mapped, or the --rate base.
Series LogTime(const TableSource& log, const LogInputOptions& options) {
  if (options.rate > 0.0) {
    const auto lengths = log.column_lengths();
    Series t;
    t.values.resize(lengths.empty() ? 0 : lengths.front());
    for (std::size_t i = 0; i < t.values.size(); ++i) t.values[i] = static_cast<double>(i) / options.rate;
    return t;
  }
  const auto mapped = options.columns.find(options.time_column);
  const std::string text = mapped != options.columns.end() ? mapped->second : options.time_column;
  return ReadExpression(log, fmt::format("‹col› {}={}", options.time_column, text), text);
}

// Linear interpolation of (t, v) at the increasing times `at`, all inside t's span.
class TimeJoinedSource : public PairedSource {
 public:
  TimeJoinedSource(std::unique_ptr<TableSource> a, std::unique_ptr<TableSource> b, const JoinTiming& timing,
                   const LogInputOptions& options);
  std::vector<std::size_t> column_lengths() const override {
    std::vector<std::size_t> lengths;
    for (auto n : a_->column_lengths()) lengths.push_back(n == a_rows_ ? end_ - begin_ : n);
    for (auto n : b_->column_lengths()) lengths.push_back(n == b_rows_ ? end_ - begin_ : n);
    return lengths;
  }
  std::vector<std::string> notes() const override {
    auto notes = a_->notes();
    notes.insert(notes.end(), notes_.begin(), notes_.end());
    for (const auto& n : b_->notes()) notes.push_back(b_->path() + ": " + n);
    return notes;
  }
  TableData Read(const std::vector<std::size_t>& columns) const override;

 private:
  std::size_t a_rows_ = 0, b_rows_ = 0;
  std::size_t begin_ = 0, end_ = 0;  // the log's rows inside the joined span
  std::vector<double> at_;           // the log's times of those rows
  std::vector<double> b_time_;       // the joined file's times on the log's clock
  std::vector<std::string> notes_;
};

// The map from the joined clock onto the log's: given, or by alignment.
ClockMap MapClocks(const TableSource& a, const TableSource& b, const Series& ta, const Series& tb,
                   const JoinTiming& timing) {
  ClockMap map;
  if (timing.shift) {
    map.offset = *timing.shift;
    map.notes.push_back(fmt::format("shifted by {:.6g} s (‹join-shift›)", *timing.shift));
    return map;
  }
  if (timing.align.empty()) return map;
  const auto eq = timing.align.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == timing.align.size()) {
    throw OptionError(fmt::format("‹join-align› {}: expected LOG_CHANNEL=JOINED_CHANNEL", timing.align));
  }
  const std::string left = timing.align.substr(0, eq), right = timing.align.substr(eq + 1);
  const Series xa = ReadExpression(a, fmt::format("‹join-align› {} (in {})", left, a.path()), left);
  const Series xb = ReadExpression(b, fmt::format("‹join-align› {} (in {})", right, b.path()), right);
  if (ta.values.size() < 16 || tb.values.size() < 16) {
    throw InputError(fmt::format("‹join-align›: {} and {} need 16 samples each to be aligned", a.path(), b.path()));
  }
  map = AlignClocks(ta.values, xa.values, tb.values, xb.values,
                    fmt::format("‹join-align› {}: {} against {}", timing.align, a.path(), b.path()));
  return map;
}

TimeJoinedSource::TimeJoinedSource(std::unique_ptr<TableSource> a, std::unique_ptr<TableSource> b,
                                   const JoinTiming& timing, const LogInputOptions& options)
    : PairedSource(std::move(a), std::move(b)) {
  if (timing.shift && !timing.align.empty()) {
    throw OptionError("‹join-shift› and ‹join-align›: give the shift or the channel to align by, not both");
  }
  const Series ta = LogTime(*a_, options);
  const Series tb = ReadExpression(*b_, fmt::format("‹join-time› {} (in {})", timing.time, b_->path()), timing.time);
  CheckIncreasing(*a_, ta, "the log's time");
  CheckIncreasing(*b_, tb, fmt::format("the joined time ‹join-time› {}", timing.time));
  a_rows_ = ta.values.size();
  b_rows_ = tb.values.size();
  const ClockMap map = MapClocks(*a_, *b_, ta, tb, timing);
  b_time_ = tb.values;
  for (double& t : b_time_) t = map.scale * t + map.offset;
  // A log sample within 1 % of a step of the joined span's ends is inside
  // it (an aligned shift is exact only to rounding).
  const double step_a = MedianStep(ta.values), step_b = map.scale * MedianStep(tb.values);
  const double slack = 0.01 * step_a;
  begin_ = 0;
  end_ = a_rows_;
  while (begin_ < end_ && ta.values[begin_] < b_time_.front() - slack) ++begin_;
  while (end_ > begin_ && ta.values[end_ - 1] > b_time_.back() + slack) --end_;
  if (end_ - begin_ < 2) {
    throw InputError(fmt::format("{}: the log spans {:.6g} .. {:.6g} s, {} spans {:.6g} .. {:.6g} s on its clock: they "
                                 "do not overlap (give the shift with ‹join-shift› or align by a channel)",
                                 a_->path(), ta.values.front(), ta.values.back(), b_->path(), b_time_.front(),
                                 b_time_.back()));
  }
  if (options.rate > 0.0 && begin_ > 0) {
    throw OptionError(fmt::format("‹rate› with ‹join-time›: {} starts {:.6g} s after the log, whose time base from "
                                  "‹rate› would then start late; give the log's time column instead",
                                  b_->path(), b_time_.front() - ta.values.front()));
  }
  at_.assign(ta.values.begin() + static_cast<std::ptrdiff_t>(begin_), ta.values.begin() + static_cast<std::ptrdiff_t>(end_));
  notes_.push_back(fmt::format("joined by time with {}: its columns interpolated linearly onto this log's time "
                               "(its time ‹join-time› {})",
                               b_->path(), timing.time));
  for (const auto& n : map.notes) notes_.push_back(b_->path() + ": " + n);
  if (begin_ > 0 || end_ < a_rows_) {
    notes_.push_back(fmt::format("{} of {} samples kept ({:.6g} .. {:.6g} s), where {} has data", end_ - begin_,
                                 a_rows_, at_.front(), at_.back(), b_->path()));
  }
  if (step_b > 1.5 * step_a) {
    notes_.push_back(fmt::format("{} is sampled at {:.4g} Hz, the log at {:.4g} Hz: its columns are interpolated "
                                 "between its samples",
                                 b_->path(), 1.0 / step_b, 1.0 / step_a));
  }
}

TableData TimeJoinedSource::Read(const std::vector<std::size_t>& columns) const {
  std::vector<std::size_t> in_a, in_b;
  Split(columns, in_a, in_b);
  TableData da = a_->Read(in_a), db = b_->Read(in_b);
  TableData out;
  const auto slice = [&](auto& v) {
    if (v.size() == a_rows_) {
      v.erase(v.begin() + static_cast<std::ptrdiff_t>(end_), v.end());
      v.erase(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(begin_));
    }
  };
  slice(da.line_numbers);
  out.line_numbers = std::move(da.line_numbers);
  std::size_t ia = 0, ib = 0;
  for (auto c : columns) {
    if (InA(c)) {
      std::vector<double>& v = da.columns[ia++];
      slice(v);
      out.columns.push_back(std::move(v));
    } else {
      const std::vector<double>& v = db.columns[ib++];
      out.columns.push_back(v.size() == b_rows_ ? InterpolateLinear(b_time_, v, at_) : v);
    }
  }
  return out;
}

}  // namespace

std::unique_ptr<TableSource> JoinSourcesByTime(std::unique_ptr<TableSource> log, std::unique_ptr<TableSource> joined,
                                               const JoinTiming& timing, const LogInputOptions& options) {
  RequireValid(options);
  return std::make_unique<TimeJoinedSource>(std::move(log), std::move(joined), timing, options);
}

}  // namespace driveid
