// Between-log disagreement (docs/models.md#adequacy): Cochran's Q and the
// random-effects widening of the joint interval, against hand-computed
// values.
#include "fit/adequacy.h"

#include <cmath>

#include <catch2/catch.hpp>

#include "fit/fit_statistics.h"

using namespace driveid;

namespace {

FitResult TwoLogs(double second_value) {
  FitResult fit;
  fit.estimates = {{"stiffness", 1.5, 0.07, 1.36, 1.64}, {"damping", 0.3, 0.01, 0.28, 0.32}};
  fit.covariance = {0.0049, 0.00035, 0.00035, 0.0001};
  fit.per_log = {{"a.csv", {{"stiffness", 1.0, 0.1, 0.8, 1.2}, {"damping", 0.3, 0.014, 0.27, 0.33}}, ""},
                 {"b.csv", {{"stiffness", second_value, 0.1, 0.8, 1.2}, {"damping", 0.3, 0.014, 0.27, 0.33}}, ""}};
  fit.heterogeneity = TestHeterogeneity(fit.per_log);
  return fit;
}

}  // namespace

TEST_CASE("logs that disagree widen the joint interval to the spread between them") {
  // 1.0 and 2.0, each +- 0.1: Q = 2 (0.5 / 0.1)^2 = 50 on 1 dof; S1 = 200,
  // S2 = 20 000, tau^2 = 49 / (200 - 100) = 0.49; std = 1 / sqrt(2 / 0.5) = 0.5.
  FitResult fit = TwoLogs(2.0);
  REQUIRE(fit.heterogeneity.size() == 2);
  CHECK(fit.heterogeneity[0].q == Approx(50.0));
  WidenForDisagreement(fit);
  const ParameterEstimate& k = fit.estimates[0];
  CHECK(k.value == 1.5);
  CHECK(k.standard_error == Approx(0.5));
  CHECK(k.ci95_high - k.value == Approx(StudentT975(1) * 0.5));
  CHECK(fit.covariance[0] == Approx(0.25));
  // The correlation with damping is kept: 0.00035 / (0.07 0.01) = 0.5.
  CHECK(fit.covariance[1] / std::sqrt(fit.covariance[0] * fit.covariance[3]) == Approx(0.5));
  // Damping, on which the logs agree, is left alone.
  CHECK(fit.estimates[1].standard_error == 0.01);
  REQUIRE(fit.notes.size() == 1);
  CHECK(fit.notes[0].find("stiffness: the logs disagree") == 0);
}

TEST_CASE("logs that agree within their std leave the interval alone") {
  FitResult fit = TwoLogs(1.2);  // Q = 2, p = 0.16
  WidenForDisagreement(fit);
  CHECK(fit.estimates[0].standard_error == 0.07);
  CHECK(fit.notes.empty());
}

TEST_CASE("residuals beyond lag-1 0.99 are named as model error, with the parameters whose intervals rest on them") {
  FitResult fit;
  fit.estimates = {{"stiffness", 94.0, 0.002, 93.99, 94.01}, {"damping", 0.02, 1e-5, 0.01998, 0.02002}};
  ChannelStatistics white, slow, short_one;
  white.name = "a.csv:shaft torque";
  white.samples = 20000;
  white.autocorrelation = 0.98;
  slow = white;
  slow.name = "b.csv:shaft torque";
  slow.autocorrelation = 0.9998;
  short_one = slow;
  short_one.samples = 10;  // too short to say
  fit.channels = {white, slow, short_one};
  const auto warnings = CheckResidualColour(fit);
  REQUIRE(warnings.size() == 1);
  CHECK_THAT(warnings[0], Catch::StartsWith("coloured residuals: b.csv:shaft torque: residual lag-1 0.9998 over 20000 "
                                            "samples (about 2 independent)"));
  CHECK_THAT(warnings[0], Catch::Contains("the intervals of stiffness, damping assume it stationary"));
}

TEST_CASE("a systematic error adds sigma^2 g g' to the covariance; stds, intervals and correlations follow") {
  FitResult fit;
  // std 0.07 and 0.01, correlation 0.5; intervals +-2 std (quantile 2).
  fit.estimates = {{"stiffness", 1.5, 0.07, 1.36, 1.64}, {"damping", 0.3, 0.01, 0.28, 0.32}};
  fit.covariance = {0.0049, 0.00035, 0.00035, 0.0001};
  fit.correlation = {1.0, 0.5, 0.5, 1.0};
  // g = (0.3, -0.02) per ms, sigma 0.2 ms: + (0.0036, -0.00024; -0.00024, 0.000016).
  AddSystematicCovariance(fit, {0.3, -0.02}, 0.2);
  const double s0 = std::sqrt(0.0049 + 0.0036), s1 = std::sqrt(0.0001 + 0.000016);
  CHECK(fit.estimates[0].standard_error == Approx(s0).epsilon(1e-12));
  CHECK(fit.estimates[1].standard_error == Approx(s1).epsilon(1e-12));
  CHECK(fit.estimates[0].ci95_high == Approx(1.5 + 2.0 * s0).epsilon(1e-12));
  CHECK(fit.estimates[1].ci95_low == Approx(0.3 - 2.0 * s1).epsilon(1e-12));
  CHECK(fit.correlation[1] == Approx((0.00035 - 0.00024) / (s0 * s1)).epsilon(1e-12));
  CHECK(fit.correlation[2] == fit.correlation[1]);
  CHECK(fit.correlation[3] == Approx(1.0));
  // A gradient of the wrong length or no sigma changes nothing.
  const FitResult before = fit;
  AddSystematicCovariance(fit, {1.0}, 1.0);
  AddSystematicCovariance(fit, {1.0, 1.0}, 0.0);
  CHECK(fit.covariance == before.covariance);
}
