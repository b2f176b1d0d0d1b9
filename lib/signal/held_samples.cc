#include "signal/held_samples.h"

#include <algorithm>
#include <cmath>

namespace driveid {
namespace {

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto middle = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), middle, v.end());
  return *middle;
}

}  // namespace

HeldChannel DetectHeldChannel(const std::vector<double>& time, const std::vector<double>& values) {
  HeldChannel out;
  const std::size_t n = std::min(time.size(), values.size());
  if (n < 100) return out;
  std::vector<double> steps, intervals, jumps;
  std::size_t repeats = 0;
  double last_change = time[0];
  for (std::size_t k = 1; k < n; ++k) {
    steps.push_back(time[k] - time[k - 1]);
    if (values[k] == values[k - 1]) {
      ++repeats;
    } else {
      intervals.push_back(time[k] - last_change);
      jumps.push_back(std::abs(values[k] - values[k - 1]));
      last_change = time[k];
    }
  }
  out.step = Median(steps);
  out.repeat_fraction = static_cast<double>(repeats) / static_cast<double>(n - 1);
  if (intervals.size() < 50) return out;
  intervals.erase(intervals.begin());  // from the first row, not from a change
  out.frame_period = Median(intervals);
  std::size_t regular = 0;
  for (double interval : intervals) {
    for (double multiple : {1.0, 2.0}) {
      if (std::abs(interval - multiple * out.frame_period) <= 0.35 * out.frame_period) {
        ++regular;
        break;
      }
    }
  }
  // A coarse encoder at a steady speed also changes at a regular interval,
  // but always by one count: frames change by what moved in a frame.
  const double quantum = *std::min_element(jumps.begin(), jumps.end());
  const auto counts = static_cast<std::size_t>(std::count_if(jumps.begin(), jumps.end(), [&](double jump) {
    return std::abs(jump - quantum) <= 1e-6 * quantum;
  }));
  out.held = out.repeat_fraction > 0.5 && out.frame_period >= 2.5 * out.step &&
             static_cast<double>(regular) >= 0.6 * static_cast<double>(intervals.size()) &&
             static_cast<double>(counts) < 0.8 * static_cast<double>(jumps.size());
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
