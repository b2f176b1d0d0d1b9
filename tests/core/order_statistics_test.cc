// The shared median and robust std (core/order_statistics.h) against values
// worked by hand and the normal distribution's quartiles.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "core/order_statistics.h"

using driveid::Median;
using driveid::RobustStd;

TEST_CASE("median: odd count, upper middle of an even count, none", "[core]") {
  CHECK(Median({3.0, -1.0, 2.0}) == 2.0);
  CHECK(Median({4.0, 1.0, 3.0, 2.0}) == 3.0);  // upper middle: one of the values
  CHECK(Median({7.5}) == 7.5);
  CHECK(Median({}) == 0.0);
  const std::vector<double> values{5.0, 1.0, 4.0};
  CHECK(Median(values) == 4.0);
  CHECK(values == std::vector<double>{5.0, 1.0, 4.0});  // taken by value: the caller's order stays
}

TEST_CASE("robust std of absolute deviations recovers a normal std", "[core]") {
  std::mt19937_64 generator(7);
  std::normal_distribution<double> normal(0.0, 2.5);
  std::vector<double> deviations(200001);
  for (double& d : deviations) d = std::abs(normal(generator));
  // MAD of N(0, s) is s x 0.67449 (the 0.75 quantile): 1.4826 x MAD = s.
  CHECK(RobustStd(deviations) == Approx(2.5).epsilon(0.01));
  CHECK(RobustStd({}) == 0.0);
}
