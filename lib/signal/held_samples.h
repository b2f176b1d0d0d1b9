// Channels a logger samples faster than the device sends them: a motor
// controller's status frame (e.g. every 20 ms) read by a 200 Hz logger
// repeats each value for several rows, and each value was measured when its
// frame was sent, not at the rows that repeat it (docs/models.md#status-frames).
// Such a log is re-timed: each value is kept once, at the row where it first
// appears (the frame's arrival, a fraction of a logger period after it was
// measured), and a value held for longer than a frame stays in once per frame
// period (the mechanism at rest sends the same value).
#pragma once

#include <cstddef>
#include <vector>

namespace driveid {

/// The thresholds of the test below (defaults: a position or velocity frame).
/// An effort frame as short as two rows (10 ms at 200 Hz) repeats only every
/// other row: {1.5, 0.4}.
struct HeldRule {
  double min_frame_steps = 2.5;      ///< frame period at least this many median steps
  double min_repeat_fraction = 0.5;  ///< more than this share of rows repeat
};

struct HeldChannel {
  bool held = false;
  double frame_period = 0.0;     ///< median interval between changes [s]
  double repeat_fraction = 0.0;  ///< share of rows that repeat the previous value
  double step = 0.0;             ///< median time step of the rows [s]
};

/// Held between frames when more than half the rows repeat the previous
/// value, the changes come at a median interval of at least 2.5 median
/// time steps, and at least 60 % of the intervals between changes lie
/// within 35 % of that median or of twice it (a fixed frame period; slow
/// motion seen through a coarse encoder repeats values at irregular
/// intervals and is not held), and fewer than 80 % of the changes are of
/// the smallest size (a coarse encoder at a steady speed changes regularly,
/// but by one count each time). Needs 50 or more changes.
HeldChannel DetectHeldChannel(const std::vector<double>& time, const std::vector<double>& values,
                              const HeldRule& rule = {});

/// The same for several logs of one device: each tested alone, then a log
/// too short for that (fewer than 100 rows or 50 changes) is held too when
/// others are, more than half its rows repeat, and its own changes (10 or
/// more) come at a median interval within 35 % of the held logs' median
/// frame period (e.g. a 1 s step test next to a long ramp).
std::vector<HeldChannel> DetectHeldChannels(const std::vector<const std::vector<double>*>& times,
                                            const std::vector<const std::vector<double>*>& values,
                                            const HeldRule& rule = {});

/// The rows to keep: where any of `channels` changes, plus one row per
/// frame period within longer runs; always the first row.
std::vector<std::size_t> FrameRows(const std::vector<double>& time, const std::vector<const std::vector<double>*>& channels,
                                   double frame_period);

}  // namespace driveid
