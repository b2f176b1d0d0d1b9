#include "signal/local_polynomial.h"

#include <cmath>

#include <catch2/catch.hpp>

using namespace driveid;

TEST_CASE("exact for quadratics, also on irregular samples, without phase lag") {
  std::vector<double> t, y;
  double time = 0.0;
  for (int k = 0; k < 400; ++k) {
    time += 0.001 * (1.0 + 0.5 * std::sin(k));  // irregular
    t.push_back(time);
    y.push_back(3.0 - 2.0 * time + 5.0 * time * time);
  }
  const auto d = EstimateDerivatives(t, y, 0.01);
  int checked = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (!d.valid[k]) continue;
    ++checked;
    CHECK(d.rate[k] == Approx(-2.0 + 10.0 * t[k]).margin(1e-9));
    CHECK(d.acceleration[k] == Approx(10.0).margin(1e-6));
  }
  CHECK(checked > 350);
  CHECK_FALSE(d.valid.front());
  CHECK_FALSE(d.valid.back());
}

TEST_CASE("13-bit encoder staircase: velocity within a few mrad/s, no lag on a sine") {
  const double quantum = 2 * M_PI / 8192;
  std::vector<double> t, y;
  for (int k = 0; k < 4000; ++k) {
    t.push_back(k * 0.001);
    y.push_back(std::floor(5.0 * std::sin(1.5 * k * 0.001) / quantum) * quantum);
  }
  const auto d = EstimateDerivatives(t, y, 0.02);
  double worst_moving = 0.0, worst_reversal = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (!d.valid[k]) continue;
    const double truth = 7.5 * std::cos(1.5 * t[k]);
    double& worst = std::abs(truth) > 0.5 ? worst_moving : worst_reversal;
    worst = std::max(worst, std::abs(d.rate[k] - truth));
  }
  // Quantisation noise: q/sqrt(12) over a +-20 ms window of 1 ms samples
  // gives a slope std of about 3 mrad/s; the worst of 4000 is about 3.5 std.
  CHECK(worst_moving < 0.015);   // rad/s, against a peak of 7.5 rad/s
  // Near a reversal the staircase is long and the estimate worse: the fits
  // exclude samples with |rate| below their threshold (0.5 rad/s by default).
  CHECK(worst_reversal < 0.03);
}
