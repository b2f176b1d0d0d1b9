#include "workflow/status_frame_logs.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/order_statistics.h"
#include "fit/core/adequacy.h"
#include "signal/held_samples.h"
#include "signal/resample.h"

namespace driveid {
namespace {

// The rows (effort) and the frames (measured q, qd) on one time line; the
// effort at a frame is the last row's at or before it, a row between frames
// carries q and qd interpolated (not compared; the simulator's grid only).
AxisLog Merge(const AxisLog& log, const std::vector<double>& frame_time, const std::vector<double>& frame_q,
              const std::vector<double>& frame_v) {
  AxisLog merged;
  merged.path = log.path;
  std::size_t j = 0;
  const auto add = [&](double t, double effort, double q, const double* v, bool measured) {
    merged.time.push_back(t);
    merged.force.push_back(effort);
    merged.position.push_back(q);
    if (v != nullptr) merged.rate.push_back(*v);
    merged.measured.push_back(measured ? 1 : 0);
  };
  for (std::size_t r = 0; r < log.time.size(); ++r) {
    while (j < frame_time.size() && frame_time[j] < log.time[r] - 1e-9) {
      add(frame_time[j], log.force[r > 0 ? r - 1 : 0], frame_q[j], frame_v.empty() ? nullptr : &frame_v[j], true);
      ++j;
    }
    if (j < frame_time.size() && std::abs(frame_time[j] - log.time[r]) <= 1e-9) {
      add(log.time[r], log.force[r], frame_q[j], frame_v.empty() ? nullptr : &frame_v[j], true);
      ++j;
      continue;
    }
    const double q = InterpolateLinear(frame_time, frame_q, {log.time[r]})[0];
    const double v = frame_v.empty() ? 0.0 : InterpolateLinear(frame_time, frame_v, {log.time[r]})[0];
    add(log.time[r], log.force[r], q, frame_v.empty() ? nullptr : &v, false);
  }
  // Frames after the last row (a positive shift) carry the last effort.
  for (; j < frame_time.size(); ++j) {
    add(frame_time[j], log.force.back(), frame_q[j], frame_v.empty() ? nullptr : &frame_v[j], true);
  }
  return merged;
}

// The effort's quantum: the smallest gap between its distinct levels, when
// every gap is a whole multiple of it (within 1 %) and there are at least
// 3 levels; else 0 (not quantised).
double EffortQuantum(const std::vector<AxisLog>& logs) {
  std::vector<double> levels;
  for (const auto& log : logs) levels.insert(levels.end(), log.force.begin(), log.force.end());
  std::sort(levels.begin(), levels.end());
  levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
  if (levels.size() < 3) return 0.0;
  double quantum = std::numeric_limits<double>::infinity();
  for (std::size_t k = 1; k < levels.size(); ++k) quantum = std::min(quantum, levels[k] - levels[k - 1]);
  if (!(quantum > 1e-12 * std::max(std::abs(levels.front()), std::abs(levels.back())))) return 0.0;
  for (std::size_t k = 1; k < levels.size(); ++k) {
    const double multiple = (levels[k] - levels[k - 1]) / quantum;
    if (std::abs(multiple - std::round(multiple)) > 0.01 * std::max(1.0, multiple)) return 0.0;
  }
  return quantum;
}

// d(estimates)/d(error) from fits with the error at +-half: `perturb`
// returns the logs with it. Empty when either fit fails.
template <class Perturb>
std::vector<double> Gradient(const Perturb& perturb, double half, const AxisSection& section,
                             const AxisParameters& fitted, const AxisOeOptions& options) {
  std::vector<double> plus, gradient;
  for (double sign : {1.0, -1.0}) {
    try {
      const FitResult fit = FitAxisOutputError(perturb(sign * half), section, &fitted, options).fit;
      for (std::size_t j = 0; j < fit.estimates.size(); ++j) {
        if (sign > 0.0) {
          plus.push_back(fit.estimates[j].value);
        } else {
          gradient.push_back((plus[j] - fit.estimates[j].value) / (2.0 * half));
        }
      }
    } catch (const IdentificationError&) {
      return {};
    }
  }
  return gradient;
}

// The robust std of a log's time steps about `step` (1.4826 x their median
// absolute deviation).
double StepScatter(const std::vector<double>& time, double step) {
  std::vector<double> deviation;
  for (std::size_t k = 1; k < time.size(); ++k) deviation.push_back(std::abs(time[k] - time[k - 1] - step));
  return RobustStd(std::move(deviation));
}

std::vector<HeldChannel> HeldChannels(const std::vector<AxisLog>& logs, std::vector<double> AxisLog::*channel,
                                      const HeldRule& rule) {
  std::vector<const std::vector<double>*> times, values;
  for (const auto& log : logs) {
    times.push_back(&log.time);
    values.push_back(&(log.*channel));
  }
  return DetectHeldChannels(times, values, rule);
}

// A log whose first row already carries its effort's level (more than half
// its largest effort): it began with its step, at its first row, and its
// effort's timing does not matter after that.
bool OpensAtLevel(const AxisLog& log) {
  if (log.force.empty()) return false;
  double largest = 0.0;
  for (double u : log.force) largest = std::max(largest, std::abs(u));
  return std::abs(log.force.front()) > 0.5 * largest;
}

// What is known of each log's timing when any log of the run is held
// (empty otherwise): which channels come in frames, where the measurements
// sit relative to the rows' effort, and how uncertain that is.
struct LogTiming {
  HeldChannel position, rate;
  double step = 0.0;          // median logger step h [s]
  double effort_frame = 0.0;  // the effort's frame period P [s], 0: at every row
  double shift = 0.0;         // the measurements' time relative to their rows [s]
  double variance = 0.0;      // of that shift's error [s^2]
};

std::vector<LogTiming> Timings(const std::vector<AxisLog>& logs) {
  const std::vector<HeldChannel> position = HeldChannels(logs, &AxisLog::position, {});
  const std::vector<HeldChannel> rate = HeldChannels(logs, &AxisLog::rate, {});
  const auto any = [](const std::vector<HeldChannel>& c) {
    return std::any_of(c.begin(), c.end(), [](const HeldChannel& h) { return h.held; });
  };
  if (!any(position) && !any(rate)) return {};
  const std::vector<HeldChannel> effort = HeldChannels(logs, &AxisLog::force, {1.5, 0.4});
  std::vector<LogTiming> out(logs.size());
  for (std::size_t i = 0; i < logs.size(); ++i) {
    LogTiming& t = out[i];
    t.position = position[i];
    t.rate = rate[i];
    t.step = MedianStep(logs[i].time);
    const double h2 = t.step * t.step;
    // A frame was sent between the row before and the row that shows it.
    if (t.position.held) t.shift -= 0.5 * t.step, t.variance += h2 / 12.0;
    if (OpensAtLevel(logs[i])) {
      // Its step began at its first row.
    } else if (effort[i].held) {
      // An effort in frames: each value sent before its row (as above) and
      // applied about its frame, or a step begun up to a frame before the
      // first row that shows it: centred, +-P/2.
      t.effort_frame = effort[i].frame_period;
      t.shift += 0.5 * t.step + 0.5 * t.effort_frame;
      t.variance += (h2 + t.effort_frame * t.effort_frame) / 12.0;
    } else if (!IsTorqueStepLog(logs[i])) {
      // A varying effort sampled at its rows from a command between them
      // (or held from them): centred on its row, +-h/2.
      t.shift += 0.5 * t.step;
      t.variance += h2 / 12.0;
    }
    // When each row's values were sampled, as uncertain as its stamp
    // scatters about a regular clock.
    const double jitter = StepScatter(logs[i].time, t.step);
    t.variance += jitter * jitter;
  }
  return out;
}

}  // namespace

StatusFrameRetiming RetimeStatusFrames(std::vector<AxisLog>& logs, const std::vector<double>& shifts) {
  StatusFrameRetiming out;
  const std::vector<LogTiming> timing = Timings(logs);
  if (timing.empty()) return out;
  for (std::size_t i = 0; i < logs.size(); ++i) {
    AxisLog& log = logs[i];
    const LogTiming& t = timing[i];
    const double shift = (i < shifts.size() ? shifts[i] : 0.0) + t.shift;
    out.effort_framed += t.effort_frame > 0.0 ? 1 : 0;
    out.effort_frame_period = std::max(out.effort_frame_period, t.effort_frame);
    std::vector<std::size_t> rows;
    if (t.position.held) {
      rows = FrameRows(log.time, {&log.position, &log.rate}, t.position.frame_period);
      out.frames += rows.size();
      out.frame_period = std::max(out.frame_period, t.position.frame_period);
      ++out.held_logs;
    } else {
      if (t.rate.held) {
        // The position is measured at every row, the rate only at frames:
        // the rate is left out (output error fits the position, inverse
        // dynamics differentiates it).
        log.start_rate = log.rate.front();
        log.rate.clear();
        ++out.held_rates;
        out.frame_period = std::max(out.frame_period, t.rate.frame_period);
      }
      if (shift == 0.0) continue;
      rows.resize(log.time.size());
      for (std::size_t k = 0; k < rows.size(); ++k) rows[k] = k;
    }
    std::vector<double> frame_time, frame_q, frame_v;
    for (std::size_t k : rows) {
      const double time = std::max(log.time.front(), log.time[k] + shift);
      if (!frame_time.empty() && time <= frame_time.back()) continue;
      frame_time.push_back(time);
      frame_q.push_back(log.position[k]);
      if (!log.rate.empty()) frame_v.push_back(log.rate[k]);
    }
    out.rows += log.time.size();
    out.logger_step = std::max(out.logger_step, t.step);
    log = Merge(log, frame_time, frame_q, frame_v);
  }
  return out;
}

std::vector<AxisLog> MeasuredRows(const std::vector<AxisLog>& logs) {
  std::vector<AxisLog> out = logs;
  for (auto& log : out) {
    if (log.measured.empty()) continue;
    AxisLog kept;
    kept.path = log.path;
    for (std::size_t k = 0; k < log.time.size(); ++k) {
      if (!log.measured[k]) continue;
      kept.time.push_back(log.time[k]);
      kept.position.push_back(log.position[k]);
      kept.force.push_back(log.force[k]);
      if (!log.rate.empty()) kept.rate.push_back(log.rate[k]);
    }
    log = std::move(kept);
  }
  return out;
}


std::string AddStatusFrameBudget(const std::vector<AxisLog>& logged, const AxisSection& section,
                                 const AxisParameters& fitted, const AxisOeOptions& options, FitResult& fit) {
  AxisOeOptions quiet = options;
  quiet.per_log = false;
  const double quantum = EffortQuantum(logged);
  std::size_t timing = 0, effort = 0, failed = 0;
  const auto add = [&](const std::vector<double>& gradient, double sigma, std::size_t& count) {
    if (gradient.empty()) {
      ++failed;
      return;
    }
    AddSystematicCovariance(fit, gradient, sigma);
    ++count;
  };
  const std::vector<LogTiming> timings = Timings(logged);
  for (std::size_t i = 0; i < timings.size(); ++i) {
    if (timings[i].variance > 0.0) {
      const auto shifted = [&](double shift) {
        std::vector<AxisLog> logs = logged;
        std::vector<double> shifts(logs.size(), 0.0);
        shifts[i] = shift;
        RetimeStatusFrames(logs, shifts);
        return logs;
      };
      add(Gradient(shifted, 0.5 * timings[i].step, section, fitted, quiet), std::sqrt(timings[i].variance), timing);
    }
    if (quantum > 0.0 && IsTorqueStepLog(logged[i])) {
      const auto moved = [&](double delta) {
        std::vector<AxisLog> logs = logged;
        for (double& u : logs[i].force) u += delta;
        RetimeStatusFrames(logs);
        return logs;
      };
      add(Gradient(moved, 0.5 * quantum, section, fitted, quiet), quantum / std::sqrt(12.0), effort);
    }
  }
  if (failed > 0) {
    fit.warnings.push_back(fmt::format("status frames: {} of the fits that size the timing and effort errors failed; "
                                       "the intervals leave those errors out and may be too narrow "
                                       "(docs/models.md#status-frames)",
                                       failed));
  }
  if (timing + effort == 0) return "";
  return fmt::format("systematic errors in the intervals (docs/models.md#status-frames): the timing of {} logs "
                     "(a frame within its logger step, a varying or framed effort within its row or frame, each row's "
                     "sample as its stamp scatters){}",
                     timing,
                     effort > 0 ? fmt::format(", the effort level of {} step logs (quantum {:.4g})", effort, quantum)
                                : "");
}

}  // namespace driveid
