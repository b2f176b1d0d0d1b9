#include "signal/resample.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/order_statistics.h"

namespace driveid {

// The median, not the mean, step: a log with a few dropped samples or a
// pause keeps its nominal rate.
double MedianStep(const std::vector<double>& time) {
  std::vector<double> steps(time.size() - 1);
  for (std::size_t k = 1; k < time.size(); ++k) steps[k - 1] = time[k] - time[k - 1];
  return Median(std::move(steps));
}

double GlitchedStep(const std::vector<double>& time) {
  if (time.size() < 3) return 0.0;
  const double median = MedianStep(time);
  std::vector<double> steps(time.size() - 1);
  for (std::size_t k = 1; k < time.size(); ++k) steps[k - 1] = time[k] - time[k - 1];
  if (!(median > 0.0)) return 0.0;
  // A stamp jittered by the logging thread is off the median by a little; a
  // step off by more than kMaxGlitch is a gap or a repeat, which resampling
  // on a uniform grid would hide, so the log is not called uniform then.
  std::size_t off = 0;
  for (double s : steps) {
    const double deviation = std::abs(s / median - 1.0);
    if (deviation > kMaxGlitch) return 0.0;
    off += deviation > 0.01;
  }
  const auto allowed = std::max<std::size_t>(3, static_cast<std::size_t>(kMaxGlitchShare * static_cast<double>(steps.size())));
  return off <= allowed ? median : 0.0;
}

std::vector<double> InterpolateLinear(const std::vector<double>& time, const std::vector<double>& values,
                                      const std::vector<double>& at) {
  std::vector<double> out(at.size());
  // One merge-like pass: `at` ascends, so the bracketing interval j only
  // moves forward (O(N + M), not a search per point). Points outside the
  // log hold its end values (the clamp), they are not extrapolated.
  std::size_t j = 0;
  for (std::size_t i = 0; i < at.size(); ++i) {
    while (j + 2 < time.size() && time[j + 1] < at[i]) ++j;
    const double w = std::clamp((at[i] - time[j]) / (time[j + 1] - time[j]), 0.0, 1.0);
    out[i] = values[j] + w * (values[j + 1] - values[j]);
  }
  return out;
}

std::vector<double> ResampleLinear(const std::vector<double>& time, const std::vector<double>& values, double rate,
                                   std::size_t count) {
  std::vector<double> at(count);
  for (std::size_t i = 0; i < count; ++i) at[i] = time.front() + static_cast<double>(i) / rate;
  return InterpolateLinear(time, values, at);
}

}  // namespace driveid
