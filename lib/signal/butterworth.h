// Zero-phase low-pass filtering of constant-rate signals: a second-order
// Butterworth section (bilinear transform with pre-warping) run forward and
// backward (filtfilt), so the result has no phase lag and a fourth-order
// magnitude roll-off with -6 dB at the cutoff. The ends are padded by odd
// reflection to avoid start-up transients.
#pragma once

#include <vector>

namespace driveid {

/// Filters `signal` sampled at `rate` Hz with cutoff `cutoff` Hz (0 < cutoff
/// < rate/2). Returns a vector of the same length.
std::vector<double> ZeroPhaseLowPass(const std::vector<double>& signal, double cutoff, double rate);
/// The same in place: besides `x`, only the padding (about 3 rate / cutoff
/// samples at each end) is held.
void ZeroPhaseLowPassInPlace(std::vector<double>& x, double cutoff, double rate);

/// Checks that `time` has a constant step within `tolerance` (relative);
/// returns the mean rate [Hz], or 0 if the sampling is irregular.
double ConstantRate(const std::vector<double>& time, double tolerance = 0.01);

}  // namespace driveid
