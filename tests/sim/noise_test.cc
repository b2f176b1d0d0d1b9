// The generators' Gaussian noise (sim/noise.h): reproducible from its seed,
// and distributed as N(0, sigma^2) with independent samples (moments, the
// 95 % band, the tails and lagged correlations of the values and of their
// squares, since Box-Muller makes them in pairs from one radius).
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "sim/noise.h"

namespace driveid {
namespace {

TEST_CASE("the same seed gives the same numbers; another seed others") {
  GaussianNoise a(42), b(42), c(43);
  int differ = 0;
  for (int k = 0; k < 1000; ++k) {
    const double x = a.Next(1.0);
    CHECK(x == b.Next(1.0));
    differ += x != c.Next(1.0) ? 1 : 0;
  }
  CHECK(differ == 1000);
  GaussianNoise zero(1);
  CHECK(zero.Next(0.0) == 0.0);
}

TEST_CASE("N(0, sigma^2): mean, variance, kurtosis, the 95 % band, the 4-sigma tails, no correlation") {
  const int n = 200000;
  const double sigma = 2.0;
  GaussianNoise noise(7);
  std::vector<double> x(n);
  for (auto& v : x) v = noise.Next(sigma);
  double mean = 0.0, m2 = 0.0, m4 = 0.0;
  int inside = 0, tails = 0, finite = 0;
  for (double v : x) {
    finite += std::isfinite(v) ? 1 : 0;
    mean += v;
    m2 += v * v;
    m4 += v * v * v * v;
    inside += std::abs(v) < 1.959964 * sigma ? 1 : 0;
    tails += std::abs(v) > 4.0 * sigma ? 1 : 0;
  }
  REQUIRE(finite == n);
  mean /= n;
  m2 /= n;
  m4 /= n;
  CHECK(std::abs(mean) < 4.0 * sigma / std::sqrt(n));
  CHECK(m2 == Approx(sigma * sigma).epsilon(4.0 * std::sqrt(2.0 / n)));  // four standard errors
  CHECK(m4 / (m2 * m2) == Approx(3.0).margin(4.0 * std::sqrt(96.0 / n)));
  CHECK(static_cast<double>(inside) / n == Approx(0.95).margin(4.0 * std::sqrt(0.95 * 0.05 / n)));
  // P(|z| > 4) = 6.33e-5: 12.7 expected; a Poisson count within 3 .. 30.
  CHECK(tails >= 3);
  CHECK(tails <= 30);
  // Lag 1 (the two of a Box-Muller pair, and the next pair's first) and
  // lag 2, of the values and of their squares: within 4 / sqrt(n) of 0.
  for (int lag : {1, 2}) {
    double r = 0.0, r_squares = 0.0;
    for (int k = 0; k + lag < n; ++k) {
      r += x[k] * x[k + lag];
      r_squares += (x[k] * x[k] - m2) * (x[k + lag] * x[k + lag] - m2);
    }
    INFO("lag " << lag);
    CHECK(std::abs(r / (n * m2)) < 4.0 / std::sqrt(n));
    CHECK(std::abs(r_squares / (n * (m4 - m2 * m2))) < 4.0 / std::sqrt(n));
  }
}

}  // namespace
}  // namespace driveid
