// Status-frame detection (signal/held_samples.h): a 200 Hz logger reading a
// 20 ms frame is held; the same motion logged at the device's rate, and a
// slow motion through a coarse encoder (repeats at irregular intervals), are
// not. Stamps jittered as roboRIO loggers write them.
#include "signal/held_samples.h"

#include <cmath>

#include <catch2/catch.hpp>

using namespace driveid;

namespace {

struct Log {
  std::vector<double> time, value;
};

// A sine position sampled at the frame times, logged at `step` with jitter.
Log Logged(double frame, double step, double resolution, double amplitude, double frequency) {
  Log log;
  unsigned state = 7;
  double t = 0.0;
  for (int k = 0; k < 2000; ++k) {
    state = state * 1103515245u + 12345u;
    const double jitter = (static_cast<double>(state >> 8 & 0xffff) / 65535.0 - 0.5) * 0.2 * step;
    const double measured_at = frame > 0.0 ? std::floor(t / frame) * frame : t;
    double q = amplitude * std::sin(2.0 * M_PI * frequency * measured_at);
    if (resolution > 0.0) q = std::round(q / resolution) * resolution;
    log.time.push_back(t);
    log.value.push_back(q);
    t += step + jitter;
  }
  return log;
}

}  // namespace

TEST_CASE("a 20 ms status frame read at 200 Hz is held; the frame period and the kept rows follow") {
  const Log framed = Logged(0.02, 0.005, 0.0, 1.0, 0.7);
  const HeldChannel h = DetectHeldChannel(framed.time, framed.value);
  CHECK(h.held);
  CHECK(h.frame_period == Approx(0.02).margin(0.003));
  CHECK(h.repeat_fraction > 0.6);
  const auto rows = FrameRows(framed.time, {&framed.value}, h.frame_period);
  CHECK(static_cast<double>(rows.size()) == Approx(static_cast<double>(framed.time.size()) / 4.0).epsilon(0.1));
}

TEST_CASE("a position logged at its own rate, or a slow one through a coarse encoder, is not held") {
  const Log direct = Logged(0.0, 0.005, 0.0, 1.0, 0.7);
  CHECK_FALSE(DetectHeldChannel(direct.time, direct.value).held);
  // 0.05 rad/s through 1/512 rev: repeats at irregular intervals.
  const Log coarse = Logged(0.0, 0.005, 2.0 * M_PI / 512.0, 0.4, 0.02);
  const HeldChannel h = DetectHeldChannel(coarse.time, coarse.value);
  INFO("repeat " << h.repeat_fraction << ", period " << h.frame_period);
  CHECK(h.repeat_fraction > 0.5);  // it does repeat, at irregular intervals
  CHECK_FALSE(h.held);
  // A steady 0.5 rad/s through 1/4096 rev: one count every 3.07 ms... every
  // 0.6 rows at 200 Hz; at 0.1 rad/s one count per 15 ms, as regular as a frame.
  Log steady;
  for (int k = 0; k < 2000; ++k) {
    const double t = 0.005 * k;
    steady.time.push_back(t);
    steady.value.push_back(std::round(0.1 * t / (2.0 * M_PI / 4096.0)) * (2.0 * M_PI / 4096.0));
  }
  const HeldChannel s = DetectHeldChannel(steady.time, steady.value);
  INFO("steady: repeat " << s.repeat_fraction << ", period " << s.frame_period);
  CHECK(s.repeat_fraction > 0.5);
  CHECK_FALSE(s.held);
}

TEST_CASE("a short log is held beside held logs of one device when its changes come at their period") {
  const Log ramp = Logged(0.02, 0.005, 0.0, 1.0, 0.7);
  Log step = Logged(0.02, 0.005, 0.0, 1.0, 2.0), direct = Logged(0.0, 0.005, 0.0, 1.0, 2.0);
  step.time.resize(150), step.value.resize(150);  // 0.75 s: fewer than 50 changes
  direct.time.resize(150), direct.value.resize(150);
  CHECK_FALSE(DetectHeldChannel(step.time, step.value).held);
  const auto held = DetectHeldChannels({&ramp.time, &step.time, &direct.time}, {&ramp.value, &step.value, &direct.value});
  REQUIRE(held.size() == 3);
  CHECK(held[0].held);
  CHECK(held[1].held);
  CHECK(held[1].frame_period == Approx(0.02).margin(0.003));
  CHECK_FALSE(held[2].held);  // logged at its own rate: no repeats
  // Alone, nothing vouches for the short log's frames.
  CHECK_FALSE(DetectHeldChannels({&step.time}, {&step.value})[0].held);
}
