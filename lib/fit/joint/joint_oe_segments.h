// Multiple shooting for the output-error joint
// (docs/models.md#joint-output-error): a log cut into segments, each
// simulated from its own initial state (fitted, not tied to the previous
// segment's end), so that the noise of a measured torque integrates only
// over one segment instead of drifting over the whole log.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "logs/joint_log.h"
#include "models/joint.h"

namespace driveid {

/// Auto segment length: this many periods of the joint's resonance, and at
/// most this many segments per log (a longer log gets longer segments: the
/// fit's nuisance parameters stay bounded).
inline constexpr double kSegmentResonancePeriods = 4.0;
inline constexpr double kMaxAutoSegments = 24.0;
/// No segment shorter than this many samples.
inline constexpr std::size_t kMinSegmentSamples = 50;

struct OeSegment {
  std::size_t begin = 0, end = 0;  ///< samples [begin, end) of the log
  std::vector<double> time;        ///< the log's times there
  std::vector<double> torque;      ///< n tau there (link side)
  std::array<double, 4> x0{};      ///< start state: theta_m, theta_m', theta_l, theta_l' (link side)
  bool motor_moving = false;       ///< its motor's start rate is estimated (else it starts at rest)
};

/// The longest log's duration [s] (0 for none).
double LongestDuration(const std::vector<JointLog>& logs);

/// The auto segment length [s]: kSegmentResonancePeriods periods of the
/// resonance sqrt(k (1/J_m + 1/J_l)) of `p`, at least the longest log's
/// duration / kMaxAutoSegments; infinite (single shooting) when `p` has no
/// resonance.
double AutoSegmentSeconds(const std::vector<JointLog>& logs, const JointParameters& p);

/// Samples per segment: `seconds` at the log's mean step, at least
/// kMinSegmentSamples; the whole log when `seconds` is infinite or longer.
std::size_t SegmentSamples(const JointLog& log, double seconds);

/// The log cut into floor(N / samples) segments of equal length (one when
/// shorter than two), each with its start state from its first samples:
/// angles as logged, rates as logged or the slope of a line through its
/// first 10 samples (a motor whose slope is within 5 standard errors of 0
/// starts at rest). `torque`: n tau for every sample.
std::vector<OeSegment> SplitLog(const JointLog& log, const std::vector<double>& torque, double n,
                                std::size_t samples);

}  // namespace driveid
