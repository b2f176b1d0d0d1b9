// The sample loop of the stick/slip simulators (sim/held_input_driver.h),
// driven here by a mass J with viscous b and Coulomb c friction written in
// the test: closed forms for sliding into rest and breaking away, one
// restart per run of equal inputs, a long run simulated in pieces equal to
// one at once, and the integrator-step budget.
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "sim/cvodes_integrator.h"
#include "sim/held_input_driver.h"

namespace driveid {
namespace {

constexpr double kJ = 0.5, kB = 0.4, kC = 0.3;

// x = (q, v); sliding in mode +-1: v' = (u - b v - c mode) / J; the root is v.
class SlidingMass final : public SensitivityOdeSystem {
 public:
  int state_size() const override { return 2; }
  int sensitivity_count() const override { return 0; }
  int root_count() const override { return 1; }
  void CalcDerivatives(double, const double* x, double* dx) const override {
    dx[0] = x[1];
    dx[1] = (u - damping * x[1] - kC * mode) / kJ;
  }
  void CalcStateJacobian(double, const double*, double* jacobian) const override {
    jacobian[0] = 0.0;
    jacobian[1] = 0.0;
    jacobian[2] = 1.0;
    jacobian[3] = -damping / kJ;
  }
  void CalcSensitivityDerivative(double, const double*, int, const double*, double* ds) const override {
    ds[0] = ds[1] = 0.0;
  }
  void CalcRoots(double, const double* x, double* g) const override { g[0] = x[1]; }
  double u = 0.0, damping = kB;
  int mode = 0;
};

class Mass final : public HeldInputSystem {
 public:
  Mass(SlidingMass& ode, CvodesIntegrator& integrator, std::size_t samples)
      : ode_(ode), integrator_(integrator), q(samples), v(samples) {}
  void SetInput(double input) override {
    ode_.u = input;
    if (x_[1] == 0.0) Decide();
  }
  bool Frozen() const override { return ode_.mode == 0; }
  void Restart(double t) override {
    ++restarts;
    integrator_.Restart(t, x_, {}, false);
  }
  void HandleSwitch() override {
    x_[0] = integrator_.state()[0];
    x_[1] = 0.0;
    Decide();
  }
  void CopyFromIntegrator() override {
    x_[0] = integrator_.state()[0];
    x_[1] = integrator_.state()[1];
  }
  void Record(std::size_t k) override {
    q[k] = x_[0];
    v[k] = x_[1];
  }
  int restarts = 0;

 private:
  void Decide() { ode_.mode = std::abs(ode_.u) <= kC ? 0 : (ode_.u > 0.0 ? 1 : -1); }
  SlidingMass& ode_;
  CvodesIntegrator& integrator_;
  double x_[2] = {0.0, 0.0};

 public:
  std::vector<double> q, v;
};

struct Run {
  std::vector<double> q, v;
  int restarts = 0, switches = 0;
};

// `pieces` > 1: RunTo in that many pieces.
Run Simulate(const std::vector<double>& time, const std::vector<double>& input, int pieces = 1, double damping = kB,
             long max_steps = 20000) {
  SlidingMass ode;
  ode.damping = damping;
  IntegratorOptions options;
  options.relative_tolerance = 1e-10;
  options.absolute_tolerance = {1e-12, 1e-12};
  options.max_steps = max_steps;
  CvodesIntegrator integrator(ode, options);
  Mass mass(ode, integrator, time.size());
  mass.Record(0);
  HeldInputRun run(integrator, time, input, mass, "test mass");
  for (int p = 1; p <= pieces; ++p) run.RunTo(time.size() * static_cast<std::size_t>(p) / static_cast<std::size_t>(pieces) - 1);
  REQUIRE(run.next() == time.size());
  return {mass.q, mass.v, mass.restarts, run.switches()};
}

TEST_CASE("break-away, sliding and sliding into rest as in closed form; one restart per run of inputs") {
  // 0 .. 1 s: u = 0.2 (held: |u| <= c); 1 .. 2 s: u = 0.8 (slides); 2 .. 6 s: u = 0.1 (slows, stops, stays).
  const double dt = 0.01;
  std::vector<double> time, input;
  for (int k = 0; k <= 600; ++k) {
    time.push_back(k * dt);
    input.push_back(k < 100 ? 0.2 : k < 200 ? 0.8 : 0.1);
  }
  const Run run = Simulate(time, input);
  CHECK(run.q[100] == 0.0);
  const double tau = kJ / kB, v_inf = (0.8 - kC) / kB, e = std::exp(-1.0 / tau);
  const double v2 = v_inf * (1.0 - e), q2 = v_inf * (1.0 - tau * (1.0 - e));
  CHECK(run.v[200] == Approx(v2).epsilon(1e-7));
  CHECK(run.q[200] == Approx(q2).epsilon(1e-7));
  // Then v_inf' = (0.1 - c) / b < 0: stops after t* = tau ln((v2 - v_inf') / -v_inf').
  const double v_slow = (0.1 - kC) / kB, t_stop = tau * std::log((v2 - v_slow) / -v_slow);
  const double q_stop = q2 + v_slow * t_stop + (v2 - v_slow) * tau * (1.0 - std::exp(-t_stop / tau));
  REQUIRE(t_stop < 4.0);
  CHECK(run.v[600] == 0.0);
  CHECK(run.q[600] == Approx(q_stop).epsilon(1e-7));
  CHECK(run.switches == 1);
  CHECK(run.restarts == 2);  // the second run of inputs, and the third (frozen runs restart nothing)
}

TEST_CASE("a long log simulated in pieces is the log simulated at once") {
  std::vector<double> time, input;
  for (int k = 0; k < 1000; ++k) {
    time.push_back(k * 0.005);
    input.push_back(0.9 * std::sin(0.7 * k * 0.005 * 6.283) + (k % 200 < 100 ? 0.2 : -0.2));  // reversals and stops
  }
  const Run once = Simulate(time, input);
  const Run pieces = Simulate(time, input, 7);
  CHECK(once.q == pieces.q);
  CHECK(once.v == pieces.v);
  CHECK(once.switches == pieces.switches);
  CHECK(once.switches > 2);
}

TEST_CASE("a trial point that makes the system too stiff fails fast with the step budget named") {
  std::vector<double> time, input;
  for (int k = 0; k < 20; ++k) {
    time.push_back(k * 1.0);
    input.push_back(k % 2 == 0 ? 5.0 : -5.0);
  }
  // (CVODES's own limit per call raised, so that the loop's budget, 2000 +
  // 200 per sample, is what stops it.)
  CHECK_THROWS_WITH(Simulate(time, input, 1, 1e9, 10000000),
                    Catch::Contains("more than 6000 integrator steps") && Catch::Contains("test mass too stiff"));
}

}  // namespace
}  // namespace driveid
