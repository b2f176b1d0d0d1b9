#include "signal/held_samples.h"

#include <algorithm>
#include <cmath>

#include "core/order_statistics.h"

namespace driveid {
namespace {

}  // namespace

namespace {

// What the test looks at: the rows' median step, the share of repeats, the
// intervals between changes (the first, from the first row, left out) and
// the sizes of the changes.
struct Changes {
  double step = 0.0, repeat_fraction = 0.0;
  std::vector<double> intervals, jumps;
};

Changes CountChanges(const std::vector<double>& time, const std::vector<double>& values) {
  Changes out;
  const std::size_t n = std::min(time.size(), values.size());
  if (n < 2) return out;
  std::vector<double> steps;
  std::size_t repeats = 0;
  double last_change = time[0];
  for (std::size_t k = 1; k < n; ++k) {
    steps.push_back(time[k] - time[k - 1]);
    if (values[k] == values[k - 1]) {
      ++repeats;
    } else {
      out.intervals.push_back(time[k] - last_change);
      out.jumps.push_back(std::abs(values[k] - values[k - 1]));
      last_change = time[k];
    }
  }
  out.step = Median(steps);
  out.repeat_fraction = static_cast<double>(repeats) / static_cast<double>(n - 1);
  if (!out.intervals.empty()) out.intervals.erase(out.intervals.begin());
  return out;
}

}  // namespace

HeldChannel DetectHeldChannel(const std::vector<double>& time, const std::vector<double>& values, const HeldRule& rule) {
  HeldChannel out;
  if (std::min(time.size(), values.size()) < 100) return out;
  const Changes c = CountChanges(time, values);
  out.step = c.step;
  out.repeat_fraction = c.repeat_fraction;
  if (c.intervals.size() < 49) return out;
  out.frame_period = Median(c.intervals);
  std::size_t regular = 0;
  for (double interval : c.intervals) {
    for (double multiple : {1.0, 2.0}) {
      if (std::abs(interval - multiple * out.frame_period) <= 0.35 * out.frame_period) {
        ++regular;
        break;
      }
    }
  }
  // A coarse encoder at a steady speed also changes at a regular interval,
  // but always by one count: frames change by what moved in a frame.
  const double quantum = *std::min_element(c.jumps.begin(), c.jumps.end());
  const auto counts = static_cast<std::size_t>(std::count_if(c.jumps.begin(), c.jumps.end(), [&](double jump) {
    return std::abs(jump - quantum) <= 1e-6 * quantum;
  }));
  out.held = out.repeat_fraction > rule.min_repeat_fraction && out.frame_period >= rule.min_frame_steps * out.step &&
             static_cast<double>(regular) >= 0.6 * static_cast<double>(c.intervals.size()) &&
             static_cast<double>(counts) < 0.8 * static_cast<double>(c.jumps.size());
  return out;
}

std::vector<HeldChannel> DetectHeldChannels(const std::vector<const std::vector<double>*>& times,
                                            const std::vector<const std::vector<double>*>& values, const HeldRule& rule) {
  std::vector<HeldChannel> out;
  std::vector<double> periods;
  for (std::size_t i = 0; i < times.size() && i < values.size(); ++i) {
    out.push_back(DetectHeldChannel(*times[i], *values[i], rule));
    if (out.back().held) periods.push_back(out.back().frame_period);
  }
  if (periods.empty()) return out;
  const double period = Median(periods);
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (out[i].held || std::min(times[i]->size(), values[i]->size()) < 20) continue;
    const Changes c = CountChanges(*times[i], *values[i]);
    if (c.intervals.size() < 10) continue;
    const double own = Median(c.intervals);
    if (c.repeat_fraction > rule.min_repeat_fraction && std::abs(own - period) <= 0.35 * period &&
        period >= rule.min_frame_steps * c.step) {
      out[i] = {true, own, c.repeat_fraction, c.step};
    }
  }
  return out;
}

std::vector<std::size_t> FrameRows(const std::vector<double>& time, const std::vector<const std::vector<double>*>& channels,
                                   double frame_period) {
  std::vector<std::size_t> rows;
  if (time.empty()) return rows;
  rows.push_back(0);
  for (std::size_t k = 1; k < time.size(); ++k) {
    const bool changed = std::any_of(channels.begin(), channels.end(), [&](const std::vector<double>* c) {
      return !c->empty() && (*c)[k] != (*c)[k - 1];
    });
    // Within a long run: the value the device keeps sending, once per frame.
    if (changed || time[k] - time[rows.back()] >= frame_period * (1.0 - 1e-9)) rows.push_back(k);
  }
  return rows;
}

}  // namespace driveid
