// LQR feedback gains (control/feedback_gains.h): WPILib SysId's published
// velocity gains, and position gains checked for optimality by simulating
// the discrete closed loop's cost directly (independent of the Riccati
// solution): any other gain costs more.
#include "control/feedback_gains.h"

#include <cmath>

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

// The first-order std of the gains against the spread of gains computed
// from (Kv, Ka) drawn with the same covariance (Box-Muller, fixed seed).
TEST_CASE("propagated gain std matches a Monte Carlo of correlated Kv, Ka") {
  const double kv = 0.18, kv_std = 0.006, ka = 0.0035, ka_std = 0.00015, rho = -0.4;
  GainRequest request;
  request.loop = FeedbackLoop::kPosition;
  request.lqr.delay = 0.01;
  const GainUncertainty g = PropagateGains(kv, kv_std, ka, ka_std, rho, request);
  unsigned long long state = 12345;
  const auto uniform = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return ((state >> 11) + 0.5) / 9007199254740992.0;
  };
  const int n = 4000;
  double sum_p = 0, sum_pp = 0, sum_d = 0, sum_dd = 0;
  for (int i = 0; i < n; ++i) {
    const double r = std::sqrt(-2.0 * std::log(uniform())), angle = 2.0 * M_PI * uniform();
    const double z1 = r * std::cos(angle), z2 = r * std::sin(angle);
    const double dv = kv_std * z1, da = ka_std * (rho * z1 + std::sqrt(1.0 - rho * rho) * z2);
    const FeedbackGains k = ControllerGains(kv + dv, ka + da, request);
    sum_p += k.kp, sum_pp += k.kp * k.kp, sum_d += k.kd, sum_dd += k.kd * k.kd;
  }
  const double sp = std::sqrt(sum_pp / n - (sum_p / n) * (sum_p / n));
  const double sd = std::sqrt(sum_dd / n - (sum_d / n) * (sum_d / n));
  INFO("kp std " << g.standard_error.kp << " vs " << sp << ", kd std " << g.standard_error.kd << " vs " << sd);
  CHECK(g.standard_error.kp == Approx(sp).epsilon(0.08));
  CHECK(g.standard_error.kd == Approx(sd).epsilon(0.08));
  CHECK(g.standard_error.kp > 0.0);
}
