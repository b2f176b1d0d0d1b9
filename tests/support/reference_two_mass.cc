#include "support/reference_two_mass.h"

#include <array>
#include <cmath>
#include <random>

#include "support/schroeder_multisine.h"

namespace driveid::testing {
namespace {

using State = std::array<double, 4>;  // th_m, th_m', th_l, th_l' (link side)

State Derivative(const TwoMassTruth& p, const State& x, double tau_m, double w) {
  const double spring = p.stiffness * (x[0] - x[2]) + p.damping * (x[1] - x[3]);
  return {x[1], (tau_m - spring - p.motor_viscous * x[1]) / p.motor_inertia, x[3], (spring - w) / p.link_inertia};
}

State Add(const State& x, const State& k, double h) {
  return {x[0] + h * k[0], x[1] + h * k[1], x[2] + h * k[2], x[3] + h * k[3]};
}

}  // namespace

TwoMassLog SimulateTwoMassClosedLoop(const TwoMassTruth& truth, const TwoMassExperiment& e) {
  std::mt19937_64 rng(e.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const auto samples = static_cast<std::size_t>(std::llround(e.duration * e.rate));
  const double dt = 1.0 / e.rate, h = dt / e.substeps;
  // Excitation: a Schroeder-phased multisine on every line of the period in
  // the band, or white noise; both scaled to the rms asked for.
  std::vector<double> r(samples, 0.0);
  if (e.excitation == Excitation::kMultisine) {
    const auto period = static_cast<std::size_t>(std::llround(e.period * e.rate));
    const std::vector<double> one = SchroederPeriod(period, e.period, e.f_min, e.f_max, e.amplitude);
    for (std::size_t i = 0; i < samples; ++i) r[i] = one[i % period];
  } else {
    for (auto& v : r) v = e.amplitude * normal(rng);
  }
  TwoMassLog log;
  State x{0.0, 0.0, 0.0, 0.0};
  double noise = 0.0, disturbance = 0.0, integral = 0.0;
  const double disturbance_ar = 0.99;
  for (std::size_t i = 0; i < samples; ++i) {
    noise = e.speed_noise_ar * noise + e.speed_noise * std::sqrt(1.0 - e.speed_noise_ar * e.speed_noise_ar) * normal(rng);
    disturbance = disturbance_ar * disturbance +
                  e.disturbance * std::sqrt(1.0 - disturbance_ar * disturbance_ar) * normal(rng);
    const double speed_measured = truth.gear_ratio * x[1] + noise;
    integral += speed_measured * dt;
    const double tau = -e.kp * speed_measured - e.ki * integral + r[i];  // motor side, held for the sample
    log.t.push_back(static_cast<double>(i) * dt);
    log.tau.push_back(tau + e.torque_noise * normal(rng));
    log.q_motor.push_back(truth.gear_ratio * x[0]);
    log.qd_motor.push_back(speed_measured);
    log.q_link.push_back(x[2]);
    log.r.push_back(r[i]);
    const double tau_m = truth.gear_ratio * tau;
    for (int s = 0; s < e.substeps; ++s) {
      const State k1 = Derivative(truth, x, tau_m, disturbance);
      const State k2 = Derivative(truth, Add(x, k1, h / 2), tau_m, disturbance);
      const State k3 = Derivative(truth, Add(x, k2, h / 2), tau_m, disturbance);
      const State k4 = Derivative(truth, Add(x, k3, h), tau_m, disturbance);
      for (int j = 0; j < 4; ++j) x[j] += h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
    }
  }
  return log;
}

}  // namespace driveid::testing
