// LQR feedback gains (control/feedback_gains.h): WPILib SysId's published
// velocity gains, and position gains checked for optimality by simulating
// the discrete closed loop's cost directly (independent of the Riccati
// solution): any other gain costs more.
#include "control/feedback_gains.h"

#include <cmath>
#include <utility>

#include <catch2/catch.hpp>

#include "core/errors.h"

using namespace driveid;

namespace {

// Sum over k of x'Qx + R u^2 for the ZOH-discretised position plant from
// x0 = [1, 0] and [0, 1] under u = -(kp x + kd v), by explicit
// discretisation (exact for this plant: x' = v, v' = -a v + b u).
double Cost(double kv, double ka, const LqrSettings& s, double kp, double kd) {
  const double alpha = kv / ka, beta = 1.0 / ka, t = s.period;
  const double e = std::exp(-alpha * t);
  // Exact ZOH for v' = -alpha v + beta u, x' = v.
  const double a11 = 1.0, a12 = (1.0 - e) / alpha, a22 = e;
  const double b1 = beta / alpha * (t - (1.0 - e) / alpha), b2 = beta / alpha * (1.0 - e);
  const double q1 = 1.0 / (s.max_position_error * s.max_position_error);
  const double q2 = 1.0 / (s.max_velocity_error * s.max_velocity_error);
  const double r = 1.0 / (s.max_effort * s.max_effort);
  double total = 0.0;
  for (int start = 0; start < 2; ++start) {
    double x = start == 0 ? 1.0 : 0.0, v = start == 1 ? 1.0 : 0.0;
    for (int k = 0; k < 20000; ++k) {
      const double u = -(kp * x + kd * v);
      total += q1 * x * x + q2 * v * v + r * u * u;
      const double xn = a11 * x + a12 * v + b1 * u, vn = a22 * v + b2 * u;
      x = xn;
      v = vn;
      if (!std::isfinite(total) || total > 1e12) return 1e12;
    }
  }
  return total;
}

}  // namespace

TEST_CASE("velocity gains equal WPILib SysId's published values") {
  LqrSettings s;  // max velocity error 1.5, max effort 7, period 0.02 s
  CHECK(VelocityLqr(3.060, 0.327, s).kp == Approx(2.11).epsilon(0.005));
  CHECK(VelocityLqr(0.0693, 0.1170, s).kp == Approx(3.11).epsilon(0.005));
}

TEST_CASE("position gains minimise the simulated LQR cost; a delay of one period is K (A - B K)") {
  for (const auto& [kv, ka] : {std::pair{3.060, 0.327}, std::pair{0.0693, 0.1170}, std::pair{1.2, 0.05}}) {
    LqrSettings s;
    s.max_position_error = 0.1;
    const FeedbackGains k = PositionLqr(kv, ka, s);
    INFO("Kv " << kv << ", Ka " << ka << ": kp " << k.kp << ", kd " << k.kd);
    REQUIRE(k.kp > 0.0);
    const double best = Cost(kv, ka, s, k.kp, k.kd);
    for (double dp : {-0.02, 0.02}) CHECK(Cost(kv, ka, s, k.kp * (1.0 + dp), k.kd) > best);
    for (double dd : {-0.02, 0.02}) CHECK(Cost(kv, ka, s, k.kp, k.kd * (1.0 + dd)) > best);
  }
  // Velocity loop, delay = one period: K (A - B K), scalar.
  LqrSettings s;
  const double kv = 3.060, ka = 0.327;
  const double k0 = VelocityLqr(kv, ka, s).kp;
  const double a = std::exp(-kv / ka * s.period), b = (1.0 - a) / kv;
  s.delay = s.period;
  CHECK(VelocityLqr(kv, ka, s).kp == Approx(k0 * (a - b * k0)).epsilon(1e-9));
}

TEST_CASE("LQR refuses a plant without inertia or a period of zero") {
  LqrSettings s;
  CHECK_THROWS_WITH(VelocityLqr(1.0, 0.0, s), Catch::Contains("Ka = 0: Kv >= 0 and Ka > 0 are required"));
  s.period = 0.0;
  CHECK_THROWS_WITH(PositionLqr(1.0, 0.1, s), "‹period› = 0: violated constraint: period > 0 s");
  s.period = 0.02;
  s.max_velocity_error = 0.0;
  CHECK_THROWS_AS(PositionLqr(1.0, 0.1, s), OptionError);
  GainRequest request;
  request.conversion = -1.0;
  CHECK_THROWS_WITH(ControllerGains(1.0, 0.1, request), "‹conversion› = -1: violated constraint: > 0");
}

// SysId's own output for two mechanisms as a team published it (Robohawk
// romi-lab, data/dadbot-3000/summary.md: "Feedback Analysis", default
// preset, period 0.02 s, no delay): a check independent of WPILib's tests.
TEST_CASE("position and velocity gains equal SysId's printed analysis of two robots") {
  GainRequest position;
  position.loop = FeedbackLoop::kPosition;
  position.lqr.max_position_error = 0.125;
  position.lqr.max_velocity_error = 1.0863;
  const FeedbackGains small = ControllerGains(2.8065, 0.59435, position);
  CHECK(small.kp == Approx(48.995).epsilon(2e-4));
  CHECK(small.kd == Approx(7.128).epsilon(2e-4));
  position.lqr.max_velocity_error = 1.2802;
  const FeedbackGains large = ControllerGains(2.3181, 0.2372, position);
  CHECK(large.kp == Approx(44.437).epsilon(2e-4));
  CHECK(large.kd == Approx(4.4068).epsilon(2e-4));
  GainRequest velocity;
  velocity.lqr.max_velocity_error = 1.2802;
  CHECK(ControllerGains(2.3181, 0.2372, velocity).kp == Approx(2.7912).epsilon(2e-4));
}

TEST_CASE("a preset scales the gains by its output and time units; Ka near 0 needs no velocity feedback") {
  const ControllerPreset* phoenix5 = FindControllerPreset("ctre-phoenix5");
  REQUIRE(phoenix5 != nullptr);
  CHECK(FindControllerPreset("no-such") == nullptr);
  GainRequest plain;
  plain.lqr.period = phoenix5->period;
  GainRequest scaled = plain;
  scaled.output_factor = phoenix5->output_factor;
  scaled.velocity_time_factor = phoenix5->velocity_time_factor;
  scaled.conversion = 2048.0;  // counts per rotation
  const double k = ControllerGains(1.0, 0.05, plain).kp;
  CHECK(ControllerGains(1.0, 0.05, scaled).kp == Approx(k * (1023.0 / 12.0) / (0.1 * 2048.0)).epsilon(1e-12));
  scaled.loop = plain.loop = FeedbackLoop::kPosition;
  scaled.normalized = false;  // kd per loop period
  CHECK(ControllerGains(1.0, 0.05, scaled).kd ==
        Approx(ControllerGains(1.0, 0.05, plain).kd * (1023.0 / 12.0) / 2048.0 / phoenix5->period).epsilon(1e-12));
  CHECK(ControllerGains(1.0, 0.0, GainRequest{}).kp == 0.0);
  GainRequest integrator;
  integrator.loop = FeedbackLoop::kPosition;
  CHECK(ControllerGains(2.0, 0.0, integrator).kp > 0.0);
}

namespace {

// An independent normal generator (LCG + Box-Muller), not SampleGains' points.
struct Normals {
  unsigned long long state;
  double Uniform() {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (static_cast<double>(state >> 11) + 0.5) / 9007199254740992.0;
  }
  std::pair<double, double> Pair() {
    const double r = std::sqrt(-2.0 * std::log(Uniform())), angle = 2.0 * M_PI * Uniform();
    return {r * std::cos(angle), r * std::sin(angle)};
  }
};

}  // namespace

// The sampled std of the gains against the spread of gains computed from
// (Kv, Ka) drawn with the same covariance by another generator.
TEST_CASE("sampled gain std matches a Monte Carlo of correlated Kv, Ka") {
  const double kv = 0.18, kv_std = 0.006, ka = 0.0035, ka_std = 0.00015, rho = -0.4;
  GainRequest request;
  request.loop = FeedbackLoop::kPosition;
  request.lqr.delay = 0.01;
  const GainUncertainty g = SampleGains(kv, kv_std, ka, ka_std, rho, request);
  Normals normals{12345};
  const int n = 4000;
  double sum_p = 0, sum_pp = 0, sum_d = 0, sum_dd = 0;
  for (int i = 0; i < n; ++i) {
    const auto [z1, z2] = normals.Pair();
    const double dv = kv_std * z1, da = ka_std * (rho * z1 + std::sqrt(1.0 - rho * rho) * z2);
    const FeedbackGains k = ControllerGains(kv + dv, ka + da, request);
    sum_p += k.kp, sum_pp += k.kp * k.kp, sum_d += k.kd, sum_dd += k.kd * k.kd;
  }
  const double sp = std::sqrt(sum_pp / n - (sum_p / n) * (sum_p / n));
  const double sd = std::sqrt(sum_dd / n - (sum_d / n) * (sum_d / n));
  INFO("kp std " << g.standard_error.kp << " vs " << sp << ", kd std " << g.standard_error.kd << " vs " << sd);
  CHECK(g.standard_error.kp == Approx(sp).epsilon(0.05));
  CHECK(g.standard_error.kd == Approx(sd).epsilon(0.05));
  CHECK(g.ci95_low.kp < g.value.kp);
  CHECK(g.value.kp < g.ci95_high.kp);
  // Deterministic: the same points every call.
  const GainUncertainty again = SampleGains(kv, kv_std, ka, ka_std, rho, request);
  CHECK(again.ci95_low.kp == g.ci95_low.kp);
  CHECK(again.ci95_high.kd == g.ci95_high.kd);
}

// Coverage: estimates of Ka with a 25 % std (a short SysId test), Kv with 3 %,
// correlated, and the measurement delay of 20 ms status frames compensated; the sampled 95 % interval of kp around each estimate holds the
// kp of the true (Kv, Ka) near 95 % of the time (value +- 1.96 first-order
// std, central differences, is printed beside it for comparison).
// 200 x 512 Riccati solutions: a ctest of its own (feedback_gains_coverage_test,
// label slow: 4 s in Release, 100 s under the sanitizers).
TEST_CASE("sampled gain intervals cover where Ka is poorly determined", "[.][coverage]") {
  const double kv = 0.125, ka = 0.0324, kv_rel = 0.03, ka_rel = 0.25, rho = -0.5;
  GainRequest request;  // velocity loop, SysId's GUI weights for a 12 V flywheel, 20 ms CAN status frames
  request.lqr.max_velocity_error = (12.0 - 0.075) / (4.0 * kv);
  request.lqr.max_effort = 7.0;
  request.lqr.delay = 0.02;
  const double truth = ControllerGains(kv, ka, request).kp;
  Normals normals{777};
  const int n = 200;
  int sampled = 0, linear = 0, used = 0;
  for (int i = 0; i < n; ++i) {
    const auto [z1, z2] = normals.Pair();
    const double kv_hat = kv * (1.0 + kv_rel * z1);
    const double ka_hat = ka * (1.0 + ka_rel * (rho * z1 + std::sqrt(1.0 - rho * rho) * z2));
    if (!(ka_hat > 0.0)) continue;
    ++used;
    const double kv_std = kv_rel * kv, ka_std = ka_rel * ka;  // a least-squares std depends on the data, not on the estimate
    const GainUncertainty g = SampleGains(kv_hat, kv_std, ka_hat, ka_std, rho, request);
    sampled += g.ci95_low.kp <= truth && truth <= g.ci95_high.kp;
    // First order, for comparison.
    const double h = 1e-6;
    const double d_kv = (ControllerGains(kv_hat * (1 + h), ka_hat, request).kp -
                         ControllerGains(kv_hat * (1 - h), ka_hat, request).kp) / (2 * h * kv_hat);
    const double d_ka = (ControllerGains(kv_hat, ka_hat * (1 + h), request).kp -
                         ControllerGains(kv_hat, ka_hat * (1 - h), request).kp) / (2 * h * ka_hat);
    const double std = std::sqrt(d_kv * d_kv * kv_std * kv_std + d_ka * d_ka * ka_std * ka_std +
                                 2 * rho * d_kv * d_ka * kv_std * ka_std);
    const double kp = ControllerGains(kv_hat, ka_hat, request).kp;
    linear += std::abs(kp - truth) <= 1.96 * std;
  }
  const double coverage = static_cast<double>(sampled) / used, first_order = static_cast<double>(linear) / used;
  INFO("sampled coverage " << coverage << ", first order " << first_order << " of " << used);
  CHECK(coverage >= 0.92);
  CHECK(coverage <= 0.985);
}
