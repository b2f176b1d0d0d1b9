// The strongest correlations of a fit (core/fit_result.h): by |r|, ties to
// the earlier pair, at most the pairs there are; a NaN correlation (an
// estimate without a std) is the weakest, never shuffling the order.
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "core/fit_result.h"

namespace driveid {
namespace {

FitResult WithCorrelation(const std::vector<double>& lower) {  // row by row below the diagonal
  FitResult fit;
  std::size_t p = 1;
  while (p * (p - 1) / 2 < lower.size()) ++p;
  REQUIRE(p * (p - 1) / 2 == lower.size());
  fit.estimates.resize(p);
  fit.correlation.assign(p * p, 0.0);
  std::size_t k = 0;
  for (std::size_t i = 0; i < p; ++i) {
    fit.correlation[i * p + i] = 1.0;
    for (std::size_t j = 0; j < i; ++j, ++k) fit.correlation[i * p + j] = fit.correlation[j * p + i] = lower[k];
  }
  return fit;
}

TEST_CASE("by |r|, strongest first; ties to the earlier pair; never more than there are") {
  // Pairs (1,0) (2,0) (2,1) (3,0) (3,1) (3,2).
  const FitResult fit = WithCorrelation({0.3, -0.9, 0.5, 0.9, -0.1, -0.5});
  const std::vector<CorrelationPair> top = StrongestCorrelations(fit, 4);
  REQUIRE(top.size() == 4);
  CHECK((top[0].first == 2 && top[0].second == 0 && top[0].correlation == -0.9));
  CHECK((top[1].first == 3 && top[1].second == 0 && top[1].correlation == 0.9));
  CHECK((top[2].first == 2 && top[2].second == 1));
  CHECK((top[3].first == 3 && top[3].second == 2));
  CHECK(StrongestCorrelations(fit, 100).size() == 6);
  CHECK(StrongestCorrelations(WithCorrelation({}), 3).empty());
  CHECK(StrongestCorrelations(fit, 0).empty());
}

TEST_CASE("a NaN correlation is the weakest") {
  const FitResult fit = WithCorrelation({std::nan(""), 0.2, std::nan(""), 0.7, 0.1, -0.4});
  const std::vector<CorrelationPair> all = StrongestCorrelations(fit, 6);
  REQUIRE(all.size() == 6);
  CHECK(all[0].correlation == 0.7);
  CHECK(all[1].correlation == -0.4);
  CHECK(all[2].correlation == 0.2);
  CHECK(all[3].correlation == 0.1);
  CHECK(std::isnan(all[4].correlation));
  CHECK(std::isnan(all[5].correlation));
  CHECK((all[4].first == 1 && all[5].first == 2));
  const std::vector<CorrelationPair> top = StrongestCorrelations(fit, 2);
  CHECK(top[0].correlation == 0.7);
  CHECK(top[1].correlation == -0.4);
}

}  // namespace
}  // namespace driveid
