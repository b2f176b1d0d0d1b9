// Zero-phase low-pass filtering of constant-rate signals: a second-order
// Butterworth section (bilinear transform with pre-warping) run forward and
// backward (filtfilt), so the result has no phase lag and a fourth-order
// magnitude roll-off with -6 dB at the cutoff. The ends are padded by odd
// reflection to avoid start-up transients.
// Documented in docs/models.md#identification.
#pragma once

#include <vector>

namespace driveid {

/// Filters `signal` sampled at `rate` Hz with cutoff `cutoff` Hz (0 < cutoff
/// < rate/2). Returns a vector of the same length.
std::vector<double> ZeroPhaseLowPass(const std::vector<double>& signal, double cutoff, double rate);
/// The same in place: besides `x`, only the padding (about 3 rate / cutoff
/// samples at each end) is held.
void ZeroPhaseLowPassInPlace(std::vector<double>& x, double cutoff, double rate);

/// The sharpened filter (Kaiser and Hamming's twicing of a symmetric
/// filter): with H the real, zero-phase response of ZeroPhaseLowPass,
/// 3 H^2 - 2 H^3, from three passes (y1 = H x, y2 = H y1, y3 = H y2;
/// 3 y2 - 2 y3). Still -6 dB at the cutoff, but the pass band is flat to
/// (1 - H)^2 (1 + 2 H) instead of 1 - H: at a quarter of the cutoff 5e-5
/// instead of 0.39 %, at half 1.0 % instead of 5.9 %; the stop band falls
/// as 3 H^2 (eighth order). Besides `x`, one copy of it is held.
void FlatZeroPhaseLowPassInPlace(std::vector<double>& x, double cutoff, double rate);
std::vector<double> FlatZeroPhaseLowPass(const std::vector<double>& signal, double cutoff, double rate);

/// Checks that `time` has a constant step within `tolerance` (relative);
/// returns the mean rate [Hz], or 0 if the sampling is irregular.
double ConstantRate(const std::vector<double>& time, double tolerance = 0.01);

}  // namespace driveid
