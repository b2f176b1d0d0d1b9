// Order statistics shared by the library: the median and the robust std.
// The median of an even count is the upper middle element (always one of
// the values, no averaging); 0 for no values.
#pragma once

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace driveid {

/// The upper median of `values` (0 for none).
inline double Median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

/// The robust std of absolute deviations: 1.4826 x their median (the
/// normal distribution's MAD factor); 0 for none.
inline double RobustStd(std::vector<double> absolute_deviations) {
  constexpr double kMadToStd = 1.4826;
  return kMadToStd * Median(std::move(absolute_deviations));
}

}  // namespace driveid
