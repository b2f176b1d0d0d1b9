// The speed loop's pieces against closed forms (control/speed_loop.h): the
// controller's polynomials against its factored form, the notch's depth and
// width, and the margins and stability of a nearly rigid joint, where the
// loop is an integrator with a delay: L = K e^(-s tau) / s with
// K = kp n^2 / (J_m + J_l) has its crossover at K, phase margin
// 90 deg - K tau, and is unstable above K = pi / (2 tau).
#include "control/speed_loop.h"

#include <cmath>
#include <complex>

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "core/errors.h"

using namespace driveid;

namespace {

SpeedLoopPlant NearlyRigid() {
  SpeedLoopPlant p;
  p.gear_ratio = 10.0;
  p.joint.motor_inertia = 0.5;
  p.joint.link_inertia = 1.5;
  p.joint.stiffness = 1e8;  // anti-resonance 1.3 kHz, far above the loop
  p.joint.damping = 2000.0;  // the resonance well damped (zeta about 0.16)
  return p;
}

}  // namespace

TEST_CASE("the PI-notch polynomials are its factored form") {
  PiNotch c;
  c.kp = 2.0;
  c.integral_corner = 5.0;
  c.notch_hz = 12.0;
  c.notch_width_hz = 4.0;
  c.notch_depth_db = 20.0;
  const double wn = 2.0 * M_PI * 12.0, zp = M_PI * 4.0 / wn, zz = zp / 10.0;
  for (double w : {0.3, 7.0, wn, 400.0}) {
    const std::complex<double> s(0.0, w);
    const std::complex<double> expected =
        c.kp * (1.0 + c.integral_corner / s) * (s * s + 2.0 * zz * wn * s + wn * wn) / (s * s + 2.0 * zp * wn * s + wn * wn);
    CHECK(std::abs(c.Evaluate(w) - expected) <= 1e-9 * std::abs(expected));
  }
  // Depth at the centre; about -3 dB at half the width either side.
  PiNotch notch = c;
  const auto gain = [&](double w) {
    return std::abs(notch.Evaluate(w)) / std::abs(notch.kp * (1.0 + notch.integral_corner / std::complex<double>(0.0, w)));
  };
  CHECK(20.0 * std::log10(gain(wn)) == Approx(-20.0).margin(0.01));
  const double half = 2.0 * M_PI * 2.0;
  CHECK(20.0 * std::log10(gain(std::sqrt(wn * wn + half * half) + half)) > -3.6);
  CHECK(20.0 * std::log10(gain(wn + 0.2 * half)) < -8.0);
}

TEST_CASE("margins of a nearly rigid joint match the integrator with delay") {
  const SpeedLoopPlant plant = NearlyRigid();
  const double period = 0.001, tau = 1.5 * period, inertia = 2.0;
  PiNotch c;
  c.notch_hz = 2000.0;  // out of the way: no depth
  c.notch_width_hz = 100.0;
  c.notch_depth_db = 0.0;
  for (double k : {50.0, 300.0}) {
    c.kp = k * inertia / 100.0;
    c.integral_corner = k / 50.0;  // costs atan(1/50) of phase, raises |L| by sqrt(1 + 1/2500)
    const LoopMargins m = EvaluateSpeedLoop(plant, c, period);
    INFO("K " << k);
    CHECK(m.stable);
    CHECK(m.crossover_hz == Approx(k / (2.0 * M_PI)).epsilon(0.01));
    CHECK(m.phase_margin_deg == Approx(90.0 - k * tau * 180.0 / M_PI - std::atan(1.0 / 50.0) * 180.0 / M_PI).margin(0.5));
    // Gain margin: the phase reaches -180 deg at pi / (2 tau), |L| = K / w there.
    CHECK(m.gain_margin_db == Approx(-20.0 * std::log10(k / (M_PI / (2.0 * tau)))).margin(0.2));
  }
  c.kp = 1.1 * (M_PI / (2.0 * tau)) * inertia / 100.0;
  c.integral_corner = 1.0;
  CHECK_FALSE(EvaluateSpeedLoop(plant, c, period).stable);
}

TEST_CASE("a designed speed loop meets its margins; a bad plant is refused") {
  SpeedLoopPlant plant;
  plant.gear_ratio = 10.0;
  plant.joint.motor_inertia = 0.5;
  plant.joint.link_inertia = 1.5;
  plant.joint.stiffness = 2000.0;
  plant.joint.damping = 2.0;
  plant.joint.motor_viscous = 6.0;
  SpeedLoopSettings s;
  const SpeedLoopDesign d = DesignSpeedLoop(plant, {}, s);
  REQUIRE(d.met);
  CHECK(d.nominal.stable);
  CHECK(d.nominal.phase_margin_deg >= 50.0);
  CHECK(d.nominal.gain_margin_db >= 6.0);
  CHECK(d.nominal.modulus_margin >= 0.5);
  CHECK(d.controller.notch_hz == Approx(std::sqrt(2000.0 * (1 / 0.5 + 1 / 1.5)) / (2.0 * M_PI)));
  // Its closed loop settles on the reference (integral action), and a gain
  // above the delay's limit diverges: the step simulation is a real loop.
  const StepResponse step = SimulateSpeedStep(plant, d.controller, s.period, 4.0);
  CHECK(std::abs(step.speed.back() - 1.0) < 0.01);
  PiNotch loud = d.controller;
  loud.kp *= 50.0;
  CHECK_FALSE(std::abs(SimulateSpeedStep(plant, loud, s.period, 1.0).speed.back()) < 10.0);  // diverged (or overflowed)
  SpeedLoopSettings no_margin = s;
  no_margin.phase_margin_deg = 95.0;
  CHECK_THROWS_WITH(DesignSpeedLoop(plant, {}, no_margin), Catch::StartsWith("‹phase_margin› = 95"));
  plant.joint.stiffness = 0.0;
  CHECK_THROWS_AS(DesignSpeedLoop(plant, {}, s), InputError);
}

namespace {

// The roots' largest magnitude of a monic-led polynomial (highest power
// first), by the companion matrix: written here, not taken from the library.
double LargestRoot(const std::vector<double>& p) {
  const Eigen::Index degree = static_cast<Eigen::Index>(p.size()) - 1;
  Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(degree, degree);
  for (Eigen::Index j = 0; j < degree; ++j) companion(0, j) = -p[static_cast<std::size_t>(j) + 1] / p[0];
  for (Eigen::Index i = 1; i < degree; ++i) companion(i, i - 1) = 1.0;
  return companion.eigenvalues().cwiseAbs().maxCoeff();
}

std::complex<double> Polyval(const std::vector<double>& lowest_first, std::complex<double> x) {
  std::complex<double> out = 0.0;
  for (std::size_t i = lowest_first.size(); i-- > 0;) out = out * x + lowest_first[i];
  return out;
}

}  // namespace

TEST_CASE("C(z) is Tustin's rule prewarped at the notch") {
  PiNotch c;
  c.kp = 2.0;
  c.integral_corner = 5.0;
  c.notch_hz = 120.0;
  c.notch_width_hz = 40.0;
  const double period = 1e-3;
  std::vector<double> b, a;
  c.Discrete(period, b, a);
  REQUIRE(b.size() == 4);
  REQUIRE(a.size() == 4);
  CHECK(a[0] == 1.0);
  // The integrator maps to z = 1: the denominator vanishes there.
  CHECK(std::abs(a[0] + a[1] + a[2] + a[3]) < 1e-12);
  const auto cz = [&](double omega) {
    const std::complex<double> x = std::exp(std::complex<double>(0.0, -omega * period));  // z^-1
    return Polyval(b, x) / Polyval(a, x);
  };
  // Exact at the notch (the prewarping); far below it, s is scaled by
  // (w_n T / 2) / tan(w_n T / 2) (0.95 here), which moves the PI's corner.
  const double wn = 2.0 * M_PI * c.notch_hz;
  CHECK(std::abs(cz(wn) - c.Evaluate(wn)) < 1e-9 * std::abs(c.Evaluate(0.3 * wn)));
  CHECK(std::abs(cz(2.0 * M_PI * 3.0) - c.Evaluate(2.0 * M_PI * 3.0)) < 0.02 * std::abs(c.Evaluate(2.0 * M_PI * 3.0)));
}

TEST_CASE("the sampled loop's stability limit is the delayed integrator's") {
  // Nearly rigid: L(z) = K T z^-(m+1) / (z - 1) with m whole periods of the
  // drive's delay; the closed loop's poles solve z^(m+1) (z - 1) + K T = 0.
  SpeedLoopPlant plant = NearlyRigid();
  const double period = 1e-3, inertia = 2.0;
  PiNotch c;
  c.notch_hz = 2000.0;
  c.notch_width_hz = 100.0;
  c.notch_depth_db = 0.0;
  c.integral_corner = 1e-3;
  for (int m : {0, 3}) {
    plant.delay = m * period;
    std::vector<double> characteristic(static_cast<std::size_t>(m) + 3, 0.0);
    characteristic[0] = 1.0;
    characteristic[1] = -1.0;
    // The critical K T by bisection on the closed form's roots.
    double low = 0.0, high = 2.0;
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (low + high);
      characteristic.back() = mid;
      (LargestRoot(characteristic) < 1.0 ? low : high) = mid;
    }
    INFO("m " << m << ", critical K T " << low);
    for (double factor : {0.9, 1.1}) {
      c.kp = factor * low / period * inertia / 100.0;
      const double radius = DiscreteLoopRadius(plant, c, period);
      CHECK((radius < 1.0) == (factor < 1.0));
      CHECK(EvaluateSpeedLoop(plant, c, period).stable == (factor < 1.0));
    }
  }
}

TEST_CASE("the step response waits out the drive's delay") {
  SpeedLoopPlant plant = NearlyRigid();
  plant.delay = 0.0034;  // 3 whole periods and a fraction
  PiNotch c;
  c.kp = 0.002;
  c.integral_corner = 1.0;
  c.notch_hz = 2000.0;
  c.notch_width_hz = 100.0;
  c.notch_depth_db = 0.0;
  const StepResponse step = SimulateSpeedStep(plant, c, 1e-3, 0.02);
  // The first command at k = 0 reaches the plant at 1 ms + 3.4 ms: the
  // speed sampled at k = 4 is still 0, at k = 5 it has moved.
  CHECK(step.speed[4] == 0.0);
  CHECK(step.speed[5] > 0.0);
}

TEST_CASE("a drive's delay the design knows keeps the loop stable; ignoring it does not") {
  SpeedLoopPlant plant;
  plant.gear_ratio = 10.0;
  plant.joint.motor_inertia = 0.5;
  plant.joint.link_inertia = 1.5;
  plant.joint.stiffness = 2000.0;
  plant.joint.damping = 2.0;
  plant.joint.motor_viscous = 6.0;
  SpeedLoopSettings s;
  const SpeedLoopDesign blind = DesignSpeedLoop(plant, {}, s);
  REQUIRE(blind.met);
  SpeedLoopPlant delayed = plant;
  delayed.delay = 0.003;
  const LoopMargins on_true = EvaluateSpeedLoop(delayed, blind.controller, s.period);
  INFO("blind design on the delayed plant: PM " << on_true.phase_margin_deg << ", GM " << on_true.gain_margin_db);
  CHECK_FALSE((on_true.stable && on_true.phase_margin_deg >= 40.0 && on_true.gain_margin_db >= 6.0));
  const SpeedLoopDesign aware = DesignSpeedLoop(delayed, {}, s);
  REQUIRE(aware.met);
  CHECK(aware.nominal.stable);
  CHECK(aware.nominal.phase_margin_deg >= 50.0);
  CHECK(aware.nominal.gain_margin_db >= 6.0);
  CHECK(aware.nominal.modulus_margin >= 0.5);
  CHECK(aware.nominal.crossover_hz < blind.nominal.crossover_hz);
  const StepResponse step = SimulateSpeedStep(delayed, aware.controller, s.period, 6.0);
  CHECK(std::abs(step.speed.back() - 1.0) < 0.01);
}
