// fit/core/omitted_terms.h: the robust Wald test of a term the fit left out.
// Under "absent" (white errors, the term's coefficient 0) W is chi^2(1):
// its mean over seeds is near 1 and it exceeds the 0.999 quantile almost
// never; with the term present it is reported missing, its coefficient
// recovered, its share of the residual sum of squares near the closed form
// c^2 var(z~) / (c^2 var(z~) + s^2); a column the fit already spans is
// dropped (dof 0).
#include "fit/core/omitted_terms.h"

#include <cmath>
#include <random>

#include <catch2/catch.hpp>

using namespace driveid;

namespace {

// y = 2 x + c z + noise; the fit estimates the x column (the true value is
// given: the residuals are those of the fitted model at its estimate).
OmittedTermTest Test(double c, unsigned seed, double* share_expected = nullptr) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss;
  LinearRegression regression({"x", "z", "twice_x"});
  regression.BeginChannel("y");
  const int n = 2000;
  const double s = 0.1;
  double zz = 0.0;
  std::vector<double> x(n), z(n), y(n);
  for (int k = 0; k < n; ++k) {
    x[k] = std::sin(0.01 * k);
    z[k] = std::cos(0.037 * k);  // nearly orthogonal to x
    y[k] = 2.0 * x[k] + c * z[k] + s * gauss(rng);
    regression.AddRow({x[k], z[k], 2.0 * x[k]}, y[k]);
    zz += z[k] * z[k];
  }
  FitOptions options;
  const FitResult fit = regression.Fit({{"x", 1.0}}, {{"z", 0.0}, {"twice_x", 0.0}}, options);
  const double b = fit.estimates[0].value;
  if (share_expected) *share_expected = c * c * zz / n / (c * c * zz / n + s * s);
  return TestOmittedTerm(regression, {"x"}, {{"x", b}, {"z", 0.0}, {"twice_x", 0.0}}, "z", {"z"});
}

}  // namespace

TEST_CASE("omitted term: chi^2(1) under absence, found with its share under presence, spanned columns dropped") {
  double mean = 0.0;
  int rejected = 0;
  const int seeds = 200;
  for (int seed = 1; seed <= seeds; ++seed) {
    const OmittedTermTest t = Test(0.0, static_cast<unsigned>(seed));
    REQUIRE(t.dof == 1);
    mean += t.wald / seeds;
    rejected += t.wald > t.critical;
    CHECK_FALSE(t.missing);
  }
  INFO("mean W " << mean << ", rejected " << rejected << " of " << seeds);
  CHECK(mean > 0.7);
  CHECK(mean < 1.4);
  CHECK(rejected <= 2);
  double share = 0.0;
  const OmittedTermTest present = Test(0.1, 3, &share);  // share 1/3: above min_share 0.1
  INFO("share " << present.share << " expected " << share << ", W " << present.wald);
  CHECK(present.missing);
  CHECK(present.coefficients[0] == Approx(0.1).margin(0.01));
  CHECK(present.share == Approx(share).margin(0.05));
  CHECK(present.critical == Approx(10.83).margin(0.01));  // chi^2(1) at 0.999
  // A column the fit spans (2 x) explains nothing new: dropped.
  LinearRegression regression({"x", "twice_x"});
  regression.BeginChannel("y");
  for (int k = 0; k < 100; ++k) regression.AddRow({std::sin(0.1 * k), 2.0 * std::sin(0.1 * k)}, std::sin(0.1 * k));
  const OmittedTermTest spanned = TestOmittedTerm(regression, {"x"}, {{"x", 1.0}, {"twice_x", 0.0}}, "2x", {"twice_x"});
  CHECK(spanned.dof == 0);
  CHECK_FALSE(spanned.missing);
}
