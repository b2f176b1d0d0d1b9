// The exact stick/slip simulation (sim/switched_linear_exact.h) on a model
// whose every motion has a closed form: a mass J with viscous b and Coulomb
// c friction under a held torque u (states 0, 1: position and rate), beside
// an undamped oscillator of angular frequency w (states 2, 3) that no mode
// touches. At rest the friction must hold N = u.
#include <cmath>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "sim/switched_linear_exact.h"

namespace driveid {
namespace {

constexpr double kJ = 0.5, kW = 3.0;

class MassWithFriction final : public SwitchedLinearModel {
 public:
  MassWithFriction(double b, double c) : b_(b), c_(c) {}
  ModeField Field(int mode) const override {
    ModeField f;
    if (mode != 0) {
      f.a(0, 1) = 1.0;
      f.a(1, 1) = -b_ / kJ;
      f.c(1) = -c_ * mode / kJ;
      f.b(1) = 1.0 / kJ;
    }
    f.a(2, 3) = 1.0;
    f.a(3, 2) = -kW * kW;
    return f;
  }
  // Sensitivity 0: b; 1: c; 2: the start position.
  ModeField FieldDerivative(int mode, int j) const override {
    ModeField g;
    if (mode != 0 && j == 0) g.a(1, 1) = -1.0 / kJ;
    if (mode != 0 && j == 1) g.c(1) = -mode / kJ;
    return g;
  }
  int InitialStateIndex(int j) const override { return j == 2 ? 0 : -1; }
  double StaticTorque(const Eigen::Vector4d&, double u) const override { return u; }
  double StaticTorqueRate(const Eigen::Vector4d&) const override { return 0.0; }
  double Coulomb() const override { return c_; }

 private:
  double b_, c_;
};

// Sliding forward from rate v0 under u < c: v(t) = v_inf + (v0 - v_inf) e^(-t/tau),
// v_inf = (u - c) / b, tau = J / b; it stops at t* = tau ln((v0 - v_inf) / -v_inf)
// having moved q* = v_inf t* + (v0 - v_inf) tau (1 - e^(-t*/tau)), and stays.
double StopTime(double b, double c, double u, double v0) {
  const double v_inf = (u - c) / b;
  return kJ / b * std::log((v0 - v_inf) / -v_inf);
}
double StopDistance(double b, double c, double u, double v0) {
  const double v_inf = (u - c) / b, tau = kJ / b, t = StopTime(b, c, u, v0);
  return v_inf * t + (v0 - v_inf) * tau * (1.0 - std::exp(-t / tau));
}

SwitchedLinearExact Run(const MassWithFriction& model, const Eigen::Vector4d& x0, double u, double step, int samples,
                        int sensitivities) {
  SwitchedLinearExact sim;
  sim.Start(model, x0, u, sensitivities, 100);
  for (int k = 0; k < samples; ++k) sim.Advance(step, u, k * step);
  return sim;
}

TEST_CASE("sliding into rest: the stop position and time in closed form; the oscillator untouched") {
  const double b = 0.4, c = 0.3, u = 0.1, v0 = 2.0;
  const MassWithFriction model(b, c);
  const Eigen::Vector4d x0(0.0, v0, 1.0, 0.0);
  // 4 s in steps of 0.01 s: the stop (t* = 1.25 ln 5 = 2.012 s) falls inside an interval.
  const SwitchedLinearExact sim = Run(model, x0, u, 0.01, 400, 3);
  REQUIRE(StopTime(b, c, u, v0) == Approx(1.25 * std::log(5.0)));
  CHECK(sim.mode() == 0);
  CHECK(sim.switches() == 1);
  CHECK(sim.state()(1) == 0.0);
  CHECK(sim.state()(0) == Approx(StopDistance(b, c, u, v0)).epsilon(1e-9));
  CHECK(sim.state()(2) == Approx(std::cos(kW * 4.0)).epsilon(1e-9));
  CHECK(sim.state()(3) == Approx(-kW * std::sin(kW * 4.0)).epsilon(1e-9));

  // Sensitivities of the position, which froze at the stop: d q*/d b and
  // d q*/d c by central differences of the closed form, and d q / d q0 = 1
  // (q' = v is 0 on both sides of the stop, so q's sensitivity does not
  // jump there; the reversal below checks the jump).
  const double h = 1e-6;
  const double dq_db = (StopDistance(b + h, c, u, v0) - StopDistance(b - h, c, u, v0)) / (2.0 * h);
  const double dq_dc = (StopDistance(b, c + h, u, v0) - StopDistance(b, c - h, u, v0)) / (2.0 * h);
  REQUIRE(sim.sensitivities().size() == 3);
  CHECK(sim.sensitivities()[0](0) == Approx(dq_db).epsilon(1e-6));
  CHECK(sim.sensitivities()[1](0) == Approx(dq_dc).epsilon(1e-6));
  CHECK(sim.sensitivities()[2](0) == Approx(1.0));
  for (int j = 0; j < 3; ++j) CHECK(sim.sensitivities()[static_cast<std::size_t>(j)](1) == 0.0);  // held at rest
  CHECK(std::abs(dq_db) > 0.1);  // (a derivative large enough to tell)
}

// Sliding forward from v0 under u < -c: it stops at t* and slides back,
// v(T) = v_back (1 - e^(-(T - t*)/tau)), v_back = (u + c) / b, and
// q(T) = q* + v_back ((T - t*) - tau (1 - e^(-(T - t*)/tau))).
Eigen::Vector2d Reversed(double b, double c, double u, double v0, double end) {
  const double t = StopTime(b, c, u, v0), tau = kJ / b, v_back = (u + c) / b, e = std::exp(-(end - t) / tau);
  return {StopDistance(b, c, u, v0) + v_back * ((end - t) - tau * (1.0 - e)), v_back * (1.0 - e)};
}

TEST_CASE("sliding into a reversal: state and sensitivities through the sensitivity jump at the stop") {
  const double b = 0.4, c = 0.3, u = -0.6, v0 = 2.0, end = 3.0;
  const MassWithFriction model(b, c);
  const SwitchedLinearExact sim = Run(model, Eigen::Vector4d(0.0, v0, 0.0, 0.0), u, 0.01, 300, 2);
  REQUIRE(StopTime(b, c, u, v0) < 1.0);
  CHECK(sim.mode() == -1);
  CHECK(sim.state().head<2>().isApprox(Reversed(b, c, u, v0, end), 1e-9));
  const double h = 1e-6;
  const Eigen::Vector2d d_db = (Reversed(b + h, c, u, v0, end) - Reversed(b - h, c, u, v0, end)) / (2.0 * h);
  const Eigen::Vector2d d_dc = (Reversed(b, c + h, u, v0, end) - Reversed(b, c - h, u, v0, end)) / (2.0 * h);
  CHECK(sim.sensitivities()[0].head<2>().isApprox(d_db, 1e-6));
  CHECK(sim.sensitivities()[1].head<2>().isApprox(d_dc, 1e-6));
}

TEST_CASE("held at rest while |u| <= c, breaking away (either way) once |u| > c") {
  const double b = 0.4, c = 0.3;
  const MassWithFriction model(b, c);
  SwitchedLinearExact sim;
  sim.Start(model, Eigen::Vector4d::Zero(), 0.2, 0, 100);
  for (int k = 0; k < 100; ++k) sim.Advance(0.01, k % 2 == 0 ? 0.3 : -0.3, k * 0.01);  // |N| = c holds
  CHECK(sim.mode() == 0);
  CHECK(sim.state().head<2>().isZero());
  for (double u : {0.8, -0.8}) {
    sim.Start(model, Eigen::Vector4d::Zero(), u, 0, 100);
    for (int k = 0; k < 100; ++k) sim.Advance(0.01, u, k * 0.01);
    // v(t) = v_inf (1 - e^(-t/tau)), q(t) = v_inf (t - tau (1 - e^(-t/tau))), t = 1 s.
    const double v_inf = (u - c * (u > 0 ? 1.0 : -1.0)) / b, tau = kJ / b;
    CHECK(sim.mode() == (u > 0 ? 1 : -1));
    CHECK(sim.state()(1) == Approx(v_inf * (1.0 - std::exp(-1.0 / tau))).epsilon(1e-10));
    CHECK(sim.state()(0) == Approx(v_inf * (1.0 - tau * (1.0 - std::exp(-1.0 / tau)))).epsilon(1e-10));
  }
}

TEST_CASE("a torque reversing every sample past the switch budget is refused as chattering") {
  const MassWithFriction model(0.4, 0.3);
  SwitchedLinearExact sim;
  sim.Start(model, Eigen::Vector4d::Zero(), 0.0, 0, 3);
  // Each interval breaks away and slides back into rest: two switches each.
  CHECK_THROWS_AS(
      [&] {
        for (int k = 0; k < 10; ++k) sim.Advance(0.5, k % 2 == 0 ? 1.0 : -1.0, k * 0.5);
      }(),
      IdentificationError);
}

}  // namespace
}  // namespace driveid
