// Time stamps as real loggers write them: a constant step with isolated
// glitches (a few intervals a few % off), and linear interpolation onto a
// regular grid for the methods that filter at a constant rate.
#pragma once

#include <cstddef>
#include <vector>

namespace driveid {

/// Largest deviation of one interval from the median step that counts as a
/// glitch (5 %), and the largest share of intervals that may deviate by more
/// than 1 % (1 %, at least 3 intervals).
constexpr double kMaxGlitch = 0.05;
constexpr double kMaxGlitchShare = 0.01;

/// The median of the intervals of `time` (at least 2 samples).
double MedianStep(const std::vector<double>& time);

/// The median step [s] when the stamps are regular but for isolated
/// glitches as above, else 0.
double GlitchedStep(const std::vector<double>& time);

/// `values` sampled at `time` (increasing, 2 or more samples), linearly
/// interpolated at the increasing times `at` (held beyond the ends).
std::vector<double> InterpolateLinear(const std::vector<double>& time, const std::vector<double>& values,
                                      const std::vector<double>& at);

/// `values` sampled at `time` (increasing), linearly interpolated at
/// t0 + k / rate for k = 0 .. count - 1 (held beyond the ends).
std::vector<double> ResampleLinear(const std::vector<double>& time, const std::vector<double>& values, double rate,
                                   std::size_t count);

}  // namespace driveid
