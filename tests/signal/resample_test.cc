// signal/resample.h: the median step and glitched stamps, and linear
// interpolation exact on a line (held beyond the ends).
#include "signal/resample.h"

#include <catch2/catch.hpp>

using namespace driveid;

TEST_CASE("resample: a line is interpolated exactly, held beyond the ends") {
  const std::vector<double> time = {0.0, 0.1, 0.25, 0.4, 0.6};
  std::vector<double> values;
  for (double t : time) values.push_back(3.0 - 2.0 * t);
  const std::vector<double> at = {-1.0, 0.05, 0.3, 0.59, 2.0};
  const std::vector<double> out = InterpolateLinear(time, values, at);
  CHECK(out[0] == Approx(3.0));  // held
  CHECK(out[1] == Approx(2.9));
  CHECK(out[2] == Approx(2.4));
  CHECK(out[3] == Approx(1.82));
  CHECK(out[4] == Approx(3.0 - 1.2));  // held
  const std::vector<double> even = ResampleLinear(time, values, 10.0, 7);
  REQUIRE(even.size() == 7);
  for (std::size_t k = 0; k < even.size(); ++k) CHECK(even[k] == Approx(3.0 - 0.2 * static_cast<double>(k)));
}

TEST_CASE("resample: median step; a regular log with one glitch has a step, an irregular one none") {
  std::vector<double> time;
  for (int k = 0; k < 1000; ++k) time.push_back(0.001 * k);
  CHECK(MedianStep(time) == Approx(0.001));
  CHECK(GlitchedStep(time) == Approx(0.001));
  time[500] += 0.00003;  // one stamp 3 % late: two intervals off by 3 %, a glitch
  CHECK(GlitchedStep(time) == Approx(0.001));
  time[500] += 0.00003;  // 6 %: beyond kMaxGlitch, no longer regular
  CHECK(GlitchedStep(time) == 0.0);
  time[500] -= 0.00006;
  for (int k = 100; k < 900; k += 100) time[k] += 0.00002;  // 16 intervals off by 2 %: more than 1 % of them
  CHECK(GlitchedStep(time) == 0.0);
  std::vector<double> irregular;
  double t = 0.0;
  for (int k = 0; k < 1000; ++k) irregular.push_back(t += (k % 2 ? 0.001 : 0.0015));
  CHECK(GlitchedStep(irregular) == 0.0);
}
