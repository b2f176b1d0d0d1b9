// Lagged products of a signal, r(l) = sum_t x_t x_{t+l} for l = 0..L,
// through the FFT of x zero-padded to the smallest power of two N >= n + L
// (so that no lag wraps around): O(N log N) for any n and L. Used by the
// period detection (signal/frequency_response) and the long-run covariance
// (fit/least_squares).
#pragma once

#include <cstddef>
#include <vector>

namespace driveid {

/// r(0..max_lag) of `x` (max_lag < x.size()); not divided by anything.
std::vector<double> LaggedProducts(const std::vector<double>& x, std::size_t max_lag);

}  // namespace driveid
