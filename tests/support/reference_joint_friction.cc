#include "support/reference_joint_friction.h"

#include <array>
#include <cmath>
#include <random>

#include "support/schroeder_multisine.h"

namespace driveid::testing {
namespace {

using State = std::array<double, 4>;  // th_m, th_m', th_l, th_l' (link side)

struct Plant {
  const FrictionJointTruth& p;
  double u = 0.0;      // n tau
  int direction = 0;   // sgn th_m' while sliding
  bool stuck = true;

  // The spring's torque at deflection D (backlash's gap and the cubic term included).
  double Spring(double deflection) const {
    double d = deflection;
    if (p.backlash > 0.0) d = std::abs(d) <= p.backlash / 2 ? 0.0 : d - std::copysign(p.backlash / 2, d);
    return p.stiffness * d + p.hardening * d * d * d;
  }
  double Ripple(const State& x) const {
    return p.ripple == 0.0 ? 0.0 : p.gear_ratio * p.ripple * std::sin(p.ripple_order * p.gear_ratio * x[0]);
  }
  State Derivative(const State& x) const {
    const double spring = Spring(x[0] - x[2]) + p.damping * (x[1] - x[3]);
    State dx{0.0, 0.0, x[3], (spring - p.link_viscous * x[3]) / p.link_inertia};
    if (!stuck) {
      dx[0] = x[1];
      dx[1] = (u + Ripple(x) - spring - p.motor_viscous * x[1] - p.motor_coulomb * direction - p.offset) /
              p.motor_inertia;
    }
    return dx;
  }
  State Rk4(const State& x, double h) const {
    const auto add = [](const State& a, const State& b, double c) {
      return State{a[0] + c * b[0], a[1] + c * b[1], a[2] + c * b[2], a[3] + c * b[3]};
    };
    const State k1 = Derivative(x), k2 = Derivative(add(x, k1, h / 2)), k3 = Derivative(add(x, k2, h / 2)),
                k4 = Derivative(add(x, k3, h));
    State out;
    for (int i = 0; i < 4; ++i) out[i] = x[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    return out;
  }
  // Torque on the resting motor other than friction.
  double Holding(const State& x) const { return u + Ripple(x) - Spring(x[0] - x[2]) + p.damping * x[3] - p.offset; }
  // At rest: stick, or slide towards the holding torque.
  void Decide(const State& x) {
    const double net = Holding(x);
    stuck = std::abs(net) <= p.motor_coulomb;
    direction = stuck ? 0 : (net > 0.0 ? 1 : -1);
  }
};

}  // namespace

FrictionJointLog SimulateFrictionJoint(const FrictionJointTruth& truth, const FrictionJointExperiment& e) {
  std::mt19937_64 rng(e.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const auto samples = static_cast<std::size_t>(std::llround(e.duration * e.rate));
  const double dt = 1.0 / e.rate, h = dt / e.substeps;
  // Schroeder multisine on every line of the period in the band.
  const auto period = static_cast<std::size_t>(std::llround(e.period * e.rate));
  const std::vector<double> one = SchroederPeriod(period, e.period, e.f_min, e.f_max, e.amplitude);
  const double motor_step = 2.0 * M_PI / e.motor_counts, link_step = 2.0 * M_PI / e.link_counts;
  const double innovation = std::sqrt(1.0 - e.noise_ar * e.noise_ar);

  FrictionJointLog log;
  Plant plant{truth};
  State x{0.0, 0.0, 0.0, 0.0};
  const double torque_innovation = std::sqrt(1.0 - e.torque_noise_ar * e.torque_noise_ar);
  double noise_m = 0.0, noise_l = 0.0, noise_tau = 0.0, integral = 0.0, previous = 0.0;
  for (std::size_t i = 0; i < samples; ++i) {
    noise_m = e.noise_ar * noise_m + e.noise * innovation * normal(rng);
    noise_l = e.noise_ar * noise_l + e.noise / truth.gear_ratio * innovation * normal(rng);
    const double t = static_cast<double>(i) * dt;
    const double q_motor = motor_step * std::round((truth.gear_ratio * x[0] + noise_m) / motor_step);
    const double q_link = link_step * std::round((x[2] + noise_l) / link_step);
    const double speed = i == 0 ? 0.0 : (q_motor - previous) / dt;
    previous = q_motor;
    const double error = e.reference_speed * std::sin(2.0 * M_PI * e.reference_hz * t) - speed;
    integral += error * dt;
    const double tau = e.kp * error + e.ki * integral + one[i % period];
    log.t.push_back(t);
    if (e.torque_noise > 0.0) {
      noise_tau = e.torque_noise_ar * noise_tau + e.torque_noise * torque_innovation * normal(rng);
    }
    log.tau.push_back(tau + noise_tau);
    log.q_motor.push_back(q_motor);
    log.q_link.push_back(q_link);
    plant.u = truth.gear_ratio * tau;
    for (int s = 0; s < e.substeps; ++s) {
      if (plant.stuck || x[1] == 0.0) plant.Decide(x);
      if (plant.stuck) {
        x = plant.Rk4(x, h);
        continue;
      }
      const State next = plant.Rk4(x, h);
      if (next[1] * plant.direction > 0.0) {
        x = next;
        continue;
      }
      // The motor's speed reaches zero within the sub-step: stop there, decide, go on.
      const double fraction = x[1] / (x[1] - next[1]);
      for (int j = 0; j < 4; ++j) x[j] += fraction * (next[j] - x[j]);
      x[1] = 0.0;
      plant.Decide(x);
      log.sticks += plant.stuck;
      x = plant.Rk4(x, (1.0 - fraction) * h);
      if (!plant.stuck && x[1] * plant.direction < 0.0) x[1] = 0.0;  // (a reversal cannot recross at once)
    }
  }
  return log;
}

}  // namespace driveid::testing
