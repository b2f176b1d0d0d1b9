// Between-log disagreement (docs/models.md#adequacy): Cochran's Q and the
// random-effects widening of the joint interval, against hand-computed
// values.
#include "fit/core/adequacy.h"

#include <cmath>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "fit/core/fit_statistics.h"

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

TEST_CASE("processing: a move past 2 std and 5 %, or past 4 std at a higher cutoff, is named; others are not") {
  // Estimates with std 1 % (inertia) and 0.05 % (viscous) of their value,
  // moved by a fit at another cutoff whose std is `other_std` x theirs.
  const auto warnings = [](double move_in_std, double other_cutoff, double other_std = 1.0) {
    FitResult fit;
    fit.estimates = {{"inertia", 1.0, 0.01, 0.98, 1.02, ""}, {"viscous", 2.0, 0.001, 1.998, 2.002, ""}};
    fit.sensitivity = {{"cutoff", {{"inertia", 1.0 + move_in_std * 0.01, other_std * 0.01, 0, 0, ""},
                                   {"viscous", 2.0 + move_in_std * 0.001, other_std * 0.001, 0, 0, ""}}, "",
                        other_cutoff}};
    return ProcessingWarnings(fit, 10.0, "advice");
  };
  // 3 std (inertia 3 %, viscous 0.15 %): neither rule, at either cutoff.
  CHECK(warnings(3.0, 20.0).empty());
  CHECK(warnings(3.0, 5.0).empty());
  // 4.5 std at twice the cutoff: both named, though under 5 %.
  const auto up = warnings(4.5, 20.0);
  REQUIRE(up.size() == 2);
  CHECK(up[0].find("processing: inertia") == 0);
  CHECK(up[0].find("4.5 std at a higher cutoff") != std::string::npos);
  CHECK(up[1].find("processing: viscous") == 0);
  CHECK(warnings(-4.5, 20.0).size() == 2);  // either direction
  // The same move at half the cutoff: the filter distorts there; not named.
  CHECK(warnings(4.5, 5.0).empty());
  // Counted in the larger std of the two fits: 4.5 of the fit's std is 3 of the other's.
  CHECK(warnings(4.5, 20.0, 1.5).empty());
  // The 5 % rule at any cutoff: inertia moved 6 % (6 std) at half the cutoff.
  const auto large = warnings(6.0, 5.0);
  REQUIRE(large.size() == 1);
  CHECK(large[0].find("processing: inertia") == 0);
  CHECK(large[0].find("by more than 5 %") != std::string::npos);
}

TEST_CASE("a parameter at its bound 0 is reported with its one-sided limit; the fit stands") {
  const auto at_bound = [](double std) {
    FitResult fit;
    fit.estimates = {{"stiffness", 100.0, 2.0, 96.0, 104.0}, {"damping", 0.0, std, -1.96 * std, 1.96 * std}};
    return fit;
  };
  // Limit 1.645 x 0.0053 = 0.0087 rules out a start of 0.05 (within 50 %): a note.
  FitResult ruled_out = at_bound(0.0053);
  REQUIRE_NOTHROW(RequireDetermined(ruled_out, {"stiffness", "damping"}, 0.5, {}, {{"damping", 0.05}}));
  CHECK(ruled_out.estimates[1].ci95_low == 0.0);
  CHECK(ruled_out.estimates[1].ci95_high == Approx(1.645 * 0.0053).epsilon(1e-3));
  CHECK(ruled_out.warnings.empty());
  REQUIRE(ruled_out.notes.size() == 1);
  CHECK_THAT(ruled_out.notes[0], Catch::Contains("damping sits at its bound 0"));
  // The same with a start of 0.01 that the limit does not rule out: still
  // reported at the bound, now with a warning that names it.
  FitResult open_start = at_bound(0.0053);
  REQUIRE_NOTHROW(RequireDetermined(open_start, {"stiffness", "damping"}, 0.5, {}, {{"damping", 0.01}}));
  CHECK(open_start.estimates[1].ci95_high == Approx(1.645 * 0.0053).epsilon(1e-3));
  REQUIRE(open_start.warnings.size() == 1);
  CHECK_THAT(open_start.warnings[0], Catch::Contains("do not rule out its start value 0.01"));
  // Without a start value (a fit that gives none) or with no finite std: refused by name.
  FitResult unknown = at_bound(0.0053);
  CHECK_THROWS_WITH(RequireDetermined(unknown, {"stiffness", "damping"}, 0.5, {}),
                    Catch::Contains("damping = 0 +- 0.0053 (at its bound 0)"));
  FitResult infinite = at_bound(INFINITY);
  CHECK_THROWS_AS(RequireDetermined(infinite, {"stiffness", "damping"}, 0.5, {}, {{"damping", 0.01}}), IdentificationError);
}

TEST_CASE("bound or refuse: the data's bound is the answer, once, after any widening; silence is refused") {
  const auto make = [](double ks, double ks_std) {
    FitResult fit;
    fit.estimates = {{"Kv", 0.125, 0.003, 0.119, 0.131}, {"Ks", ks, ks_std, ks - 1.96 * ks_std, ks + 1.96 * ks_std}};
    return fit;
  };
  // At its bound 0: [0, 1.645 std], one warning naming it; the other untouched.
  FitResult at_bound = make(0.0, 0.11);
  REQUIRE_NOTHROW(BoundOrRefuse(at_bound, {"Kv", "Ks"}, 0.5, {}));
  CHECK(at_bound.estimates[1].ci95_low == 0.0);
  CHECK(at_bound.estimates[1].ci95_high == Approx(1.6448536 * 0.11));
  CHECK(at_bound.estimates[0].ci95_low == 0.119);
  REQUIRE(at_bound.warnings.size() == 1);
  CHECK_THAT(at_bound.warnings[0], Catch::StartsWith("bounded only: Ks = 0 +- 0.11 (at its bound 0"));
  // Above 0 with a relative std above 50 %: the two-sided interval cut at 0.
  FitResult loose = make(0.05, 0.04);
  REQUIRE_NOTHROW(BoundOrRefuse(loose, {"Kv", "Ks"}, 0.5, {}));
  CHECK(loose.estimates[1].ci95_low == 0.0);
  CHECK(loose.estimates[1].ci95_high == Approx(0.05 + 1.96 * 0.04));
  REQUIRE(loose.warnings.size() == 1);
  CHECK_THAT(loose.warnings[0], Catch::Contains("relative std 80 %"));
  // Determined: nothing changes.
  FitResult determined = make(0.075, 0.03);
  REQUIRE_NOTHROW(BoundOrRefuse(determined, {"Kv", "Ks"}, 0.5, {}));
  CHECK(determined.warnings.empty());
  CHECK(determined.estimates[1].ci95_low == Approx(0.075 - 1.96 * 0.03));
  // Widened afterwards (std 0.03 -> 0.06, above 50 %): applied again, bounded;
  // applied twice, one warning with the latest numbers.
  determined.estimates[1].standard_error = 0.06;
  BoundOrRefuse(determined, {"Kv", "Ks"}, 0.5, {});
  determined.estimates[1].standard_error = 0.07;
  BoundOrRefuse(determined, {"Kv", "Ks"}, 0.5, {});
  REQUIRE(determined.warnings.size() == 1);
  CHECK_THAT(determined.warnings[0], Catch::Contains("Ks = 0.075 +- 0.07"));
  CHECK(determined.estimates[1].ci95_high == Approx(0.075 + 1.96 * 0.07));
  // The data say nothing: no finite std, or the fit says why (silent): refused by name.
  FitResult infinite = make(0.0, INFINITY);
  try {
    BoundOrRefuse(infinite, {"Kv", "Ks"}, 0.5, {"a context warning"});
    FAIL("no refusal");
  } catch (const IdentificationError& e) {
    CHECK(e.parameters() == std::vector<std::string>{"Ks"});
    CHECK_THAT(e.what(), Catch::Contains("warning: a context warning"));
  }
  FitResult silent = make(0.05, 0.04);
  CHECK_THROWS_WITH(BoundOrRefuse(silent, {"Kv", "Ks"}, 0.5, {}, {{"Ks", "no motion in both directions"}}),
                    Catch::Contains("Ks = 0.05 +- 0.04 (relative std 80 %): no motion in both directions"));
  // A parameter not bounded at 0 is never touched.
  FitResult signed_offset = make(0.0, 0.11);
  REQUIRE_NOTHROW(BoundOrRefuse(signed_offset, {"Kv"}, 0.5, {}));
  CHECK(signed_offset.warnings.empty());
  CHECK(signed_offset.estimates[1].ci95_low < 0.0);
}

TEST_CASE("processing: a move past the std widens the covariance by the candidates' spread; a small one does not") {
  FitResult fit;
  fit.estimates = {{"viscous", 191.6, 4.2, 191.6 - 1.96 * 4.2, 191.6 + 1.96 * 4.2}, {"coulomb", 20.0, 0.5, 19.02, 20.98}};
  fit.covariance = {4.2 * 4.2, 0.3 * 4.2 * 0.5, 0.3 * 4.2 * 0.5, 0.25};
  fit.correlation = {1.0, 0.3, 0.3, 1.0};
  FitResult quiet = fit;
  fit.sensitivity = {{"cutoff 20 Hz", {{"viscous", 204.5, 4.0, 0, 0}, {"coulomb", 19.6, 0.5, 0, 0}}, "", 20.0},
                     {"cutoff 80 Hz", {{"viscous", 190.0, 4.5, 0, 0}, {"coulomb", 20.1, 0.5, 0, 0}}, "", 80.0}};
  REQUIRE(WidenForProcessing(fit, 40.0));
  // By hand: the covariance gains sum_i (theta_i - theta)(theta_i - theta)' / 2.
  const double dv[2] = {204.5 - 191.6, 190.0 - 191.6}, dc[2] = {19.6 - 20.0, 20.1 - 20.0};
  const double vv = 4.2 * 4.2 + (dv[0] * dv[0] + dv[1] * dv[1]) / 2.0;
  const double cc = 0.25 + (dc[0] * dc[0] + dc[1] * dc[1]) / 2.0;
  const double vc = 0.3 * 4.2 * 0.5 + (dv[0] * dc[0] + dv[1] * dc[1]) / 2.0;
  CHECK(fit.covariance[0] == Approx(vv));
  CHECK(fit.covariance[3] == Approx(cc));
  CHECK(fit.covariance[1] == Approx(vc));
  CHECK(fit.estimates[0].standard_error == Approx(std::sqrt(vv)));
  // The reference 203.5 now lies inside the viscous interval.
  CHECK(fit.estimates[0].ci95_low < 203.5);
  CHECK(203.5 < fit.estimates[0].ci95_high);
  REQUIRE(fit.notes.size() == 1);
  CHECK_THAT(fit.notes[0], Catch::Contains("viscous x"));
  // Moves within the std: nothing changes.
  quiet.sensitivity = {{"cutoff 20 Hz", {{"viscous", 193.0, 4.0, 0, 0}, {"coulomb", 20.2, 0.5, 0, 0}}, "", 20.0}};
  CHECK_FALSE(WidenForProcessing(quiet, 40.0));
  CHECK(quiet.covariance[0] == 4.2 * 4.2);
  // A failed candidate is left out.
  quiet.sensitivity.push_back({"cutoff 80 Hz", {}, "refused", 80.0});
  CHECK_FALSE(WidenForProcessing(quiet, 40.0));
}
