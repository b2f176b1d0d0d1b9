// One period of a Schroeder-phased multisine for the tests' own generators:
// every line l / period in [f_min, f_max] with phase -pi (l - first)(l - first + 1) / lines,
// scaled to the rms asked for. Written from the definition, not from lib/.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

namespace driveid::testing {

inline std::vector<double> SchroederPeriod(std::size_t period_samples, double period_s, double f_min, double f_max,
                                           double rms) {
  const int first = static_cast<int>(std::ceil(f_min * period_s)), last = static_cast<int>(f_max * period_s);
  const int lines = last - first + 1;
  std::vector<double> one(period_samples, 0.0);
  double power = 0.0;
  for (std::size_t i = 0; i < period_samples; ++i) {
    for (int l = first; l <= last; ++l) {
      const double phase = -M_PI * (l - first) * (l - first + 1) / lines;
      one[i] += std::cos(2.0 * M_PI * l * static_cast<double>(i) / static_cast<double>(period_samples) + phase);
    }
    power += one[i] * one[i];
  }
  const double scale = rms / std::sqrt(power / static_cast<double>(period_samples));
  for (double& v : one) v *= scale;
  return one;
}

}  // namespace driveid::testing
