#include "signal/local_polynomial.h"

#include <Eigen/Dense>

namespace driveid {

SignalDerivatives EstimateDerivatives(const std::vector<double>& time, const std::vector<double>& signal,
                                      double half_window) {
  const std::size_t n = time.size();
  SignalDerivatives out;
  out.value.assign(n, 0.0);
  out.rate.assign(n, 0.0);
  out.acceleration.assign(n, 0.0);
  out.valid.assign(n, 0);
  std::size_t first = 0, last = 0;  // window [first, last)
  for (std::size_t i = 0; i < n; ++i) {
    while (time[i] - time[first] > half_window) ++first;
    if (last < i + 1) last = i + 1;
    while (last < n && time[last] - time[i] <= half_window) ++last;
    // Normal equations in x = (t - t_i) / h: well conditioned for any h.
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    Eigen::Vector3d right = Eigen::Vector3d::Zero();
    for (std::size_t j = first; j < last; ++j) {
      const double x = (time[j] - time[i]) / half_window;
      const Eigen::Vector3d basis(1.0, x, x * x);
      normal.noalias() += basis * basis.transpose();
      right.noalias() += basis * signal[j];
    }
    const std::size_t before = i - first, after = last - 1 - i;
    const bool centred = time[i] - time[first] >= 0.75 * half_window && time[last - 1] - time[i] >= 0.75 * half_window;
    if (before < 2 || after < 2 || !centred) {
      // No centred window (log ends, gaps): fall back to the raw value.
      out.value[i] = signal[i];
      continue;
    }
    const Eigen::Vector3d c = normal.ldlt().solve(right);
    out.value[i] = c(0);
    out.rate[i] = c(1) / half_window;
    out.acceleration[i] = 2.0 * c(2) / (half_window * half_window);
    out.valid[i] = 1;
  }
  return out;
}

}  // namespace driveid
