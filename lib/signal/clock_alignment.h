// Aligning two logs written on different clocks (docs/formats.md#joining-by-time)
// by a channel both record (a motor speed, a position): the normalised
// cross-correlation over every shift that leaves half the shorter record
// overlapping, its peak refined by a parabola through the three lags around
// it and then on the first record's own samples, and the clocks' rate
// difference from the shifts of the thirds. The map is
// a-time = scale * b-time + offset.
#pragma once

#include <string>
#include <vector>

namespace driveid {

/// The shift s with b(t - s) closest to a(t): a-time = b-time + s.
struct ChannelShift {
  double shift = 0.0;        ///< [s]
  double correlation = 0.0;  ///< normalised correlation at the peak (1: identical up to gain and offset)
  /// The highest peak outside the main one's lobe (a periodic channel
  /// has one a period away): its shift and correlation (0 when none).
  double runner_up_shift = 0.0;
  double runner_up_correlation = 0.0;
  double step = 0.0;  ///< [s] the common grid the correlation was taken on
};

/// Normalised cross-correlation of (ta, xa) and (tb, xb), each with
/// strictly increasing times and at least 16 samples, resampled linearly
/// onto the coarser median step; O(N log N) through the FFT.
ChannelShift ShiftByCrossCorrelation(const std::vector<double>& ta, const std::vector<double>& xa,
                                     const std::vector<double>& tb, const std::vector<double>& xb);

/// a-time = scale * b-time + offset.
struct ClockMap {
  double scale = 1.0;
  double offset = 0.0;
  double correlation = 0.0;  ///< of the whole records at their best shift
  /// What was measured, for the log's notes.
  std::vector<std::string> notes;
};

/// Smallest peak correlation for an alignment, and the margin by which the
/// main peak must stand above the runner-up.
inline constexpr double kMinAlignmentCorrelation = 0.5;
inline constexpr double kMinAlignmentMargin = 0.05;

/// The clock map that aligns b onto a: the whole records' shift, then each third of a
/// against b near it; when the first and last differ by more than a tenth
/// of a grid step and four times the middle's distance from their line,
/// the clocks run at different rates and the map takes that line. Throws IdentificationError (naming `what`)
/// when the peak correlation is below kMinAlignmentCorrelation or a second
/// peak comes within kMinAlignmentMargin of it (a periodic channel);
/// InputError when a record's stamps have gaps (span over 4 x its samples
/// at the common step).
ClockMap AlignClocks(const std::vector<double>& ta, const std::vector<double>& xa, const std::vector<double>& tb,
                     const std::vector<double>& xb, const std::string& what);

}  // namespace driveid
