// sim/joint_exact_simulator.h: the two-mass joint without Coulomb friction
// (linear) against an RK4 integration written here of
//   J_m theta_m'' = tau_m - k D - d D' - b_m theta_m' - tau_0
//   J_l theta_l'' = k D + d D' - b_l theta_l',   D = theta_m - theta_l,
// with the torque held over each sample; its sensitivities against central
// differences of its own states.
#include "sim/joint_exact_simulator.h"

#include <cmath>

#include <catch2/catch.hpp>

#include "sim/joint_simulator.h"

using namespace driveid;

namespace {

using State = std::array<double, 4>;

State Derivative(const JointParameters& p, const State& x, double tau) {
  const double d = x[0] - x[2], dd = x[1] - x[3];
  const double spring = p.stiffness * d + p.damping * dd;
  return {x[1], (tau - spring - p.motor_viscous * x[1] - p.offset) / p.motor_inertia, x[3],
          (spring - p.link_viscous * x[3]) / p.link_inertia};
}

std::vector<State> Rk4(const JointParameters& p, const std::vector<double>& time, const std::vector<double>& tau,
                       State x) {
  std::vector<State> out = {x};
  for (std::size_t k = 0; k + 1 < time.size(); ++k) {
    const int steps = 200;
    const double h = (time[k + 1] - time[k]) / steps;
    for (int s = 0; s < steps; ++s) {
      const auto add = [](const State& a, const State& b, double f) {
        return State{a[0] + f * b[0], a[1] + f * b[1], a[2] + f * b[2], a[3] + f * b[3]};
      };
      const State k1 = Derivative(p, x, tau[k]);
      const State k2 = Derivative(p, add(x, k1, h / 2), tau[k]);
      const State k3 = Derivative(p, add(x, k2, h / 2), tau[k]);
      const State k4 = Derivative(p, add(x, k3, h), tau[k]);
      for (int i = 0; i < 4; ++i) x[i] += h / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    }
    out.push_back(x);
  }
  return out;
}

JointParameters Linear() {
  JointParameters p{};
  p.motor_inertia = 0.02;
  p.link_inertia = 0.05;
  p.stiffness = 20.0;
  p.damping = 0.05;
  p.motor_viscous = 0.1;
  p.link_viscous = 0.05;
  p.offset = 0.02;
  return p;
}

}  // namespace

TEST_CASE("exact joint simulator: the linear joint against RK4, sensitivities against differences") {
  const JointParameters p = Linear();
  std::vector<double> time, tau;
  for (int k = 0; k < 400; ++k) {
    time.push_back(0.002 * k);
    tau.push_back(0.3 * std::sin(2.0 * M_PI * 3.0 * 0.002 * k) + (k > 200 ? 0.2 : 0.0));
  }
  const State x0 = {0.01, 0.0, 0.0, 0.02};
  JointExactSimulator simulator({kJointStiffness, kJointMotorInertia});
  JointStateResponse response;
  simulator.Simulate(p, time, tau, x0, true, &response);
  const std::vector<State> reference = Rk4(p, time, tau, x0);
  REQUIRE(response.state.size() == 4 * time.size());
  for (std::size_t k = 0; k < time.size(); k += 7) {
    for (int i = 0; i < 4; ++i) {
      INFO("sample " << k << " state " << i);
      CHECK(response.state[4 * k + i] == Approx(reference[k][i]).margin(1e-9));
    }
  }
  // d x / d k and d x / d J_m by central differences of the simulator's own states.
  for (const auto& [index, member] : {std::pair{0, &JointParameters::stiffness},
                                      std::pair{1, &JointParameters::motor_inertia}}) {
    const double h = 1e-6 * (p.*member);
    JointParameters up = p, down = p;
    up.*member += h;
    down.*member -= h;
    JointStateResponse a, b;
    simulator.Simulate(up, time, tau, x0, false, &a);
    simulator.Simulate(down, time, tau, x0, false, &b);
    for (std::size_t k = 50; k < time.size(); k += 50) {
      for (int i = 0; i < 4; ++i) {
        const double difference = (a.state[4 * k + i] - b.state[4 * k + i]) / (2.0 * h);
        INFO("term " << index << " sample " << k << " state " << i);
        CHECK(response.sensitivity[(k * 2 + index) * 4 + i] == Approx(difference).epsilon(1e-4).margin(1e-8));
      }
    }
  }
}
