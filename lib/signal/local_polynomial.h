// Zero-phase differentiation of sampled signals (e.g. quantised encoder
// angles): at each sample, a quadratic is fitted by least squares to the
// samples within +-half_window seconds, on their actual time stamps
// (Savitzky-Golay generalised to irregular sampling). Rate = slope and
// acceleration = twice the curvature at the centre. A centred window has no
// phase lag; the velocity bias is ~ psi''' h^2 / 10, the acceleration bias
// ~ psi'''' h^2 / 14, and quantisation noise q/sqrt(12) is averaged over
// the window.
// Documented in docs/models.md#identification.
#pragma once

#include <vector>

namespace driveid {

struct SignalDerivatives {
  std::vector<double> value;         ///< smoothed signal
  std::vector<double> rate;          ///< first derivative [unit/s]
  std::vector<double> acceleration;  ///< second derivative [unit/s^2]
  std::vector<char> valid;           ///< 1 where the window is centred: >= 2 samples and >= 3/4 h on each side
};

/// Estimates value, rate and acceleration; `half_window` > 0 in seconds.
/// `time` strictly increasing, same length as `signal`.
SignalDerivatives EstimateDerivatives(const std::vector<double>& time, const std::vector<double>& signal,
                                      double half_window);

}  // namespace driveid
