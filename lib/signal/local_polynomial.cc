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
    // Normal equations in x = (t - t_i) / h (well conditioned for any h):
    // power sums of x and moments of the signal, then a symmetric 3x3 solve.
    double s0 = 0, s1 = 0, s2 = 0, s3 = 0, s4 = 0, m0 = 0, m1 = 0, m2 = 0;
    const double scale = 1.0 / half_window;
    for (std::size_t j = first; j < last; ++j) {
      const double x = (time[j] - time[i]) * scale;
      const double x2 = x * x;
      const double y = signal[j] - signal[i];  // offset for accuracy; added back below
      s0 += 1.0;
      s1 += x;
      s2 += x2;
      s3 += x2 * x;
      s4 += x2 * x2;
      m0 += y;
      m1 += x * y;
      m2 += x2 * y;
    }
    const std::size_t before = i - first, after = last - 1 - i;
    const bool centred = time[i] - time[first] >= 0.75 * half_window && time[last - 1] - time[i] >= 0.75 * half_window;
    if (before < 2 || after < 2 || !centred) {
      // No centred window (log ends, gaps): fall back to the raw value.
      out.value[i] = signal[i];
      continue;
    }
    Eigen::Matrix3d normal;
    normal << s0, s1, s2, s1, s2, s3, s2, s3, s4;
    const Eigen::Vector3d c = normal.ldlt().solve(Eigen::Vector3d(m0, m1, m2));
    out.value[i] = signal[i] + c(0);
    out.rate[i] = c(1) / half_window;
    out.acceleration[i] = 2.0 * c(2) / (half_window * half_window);
    out.valid[i] = 1;
  }
  return out;
}

}  // namespace driveid
