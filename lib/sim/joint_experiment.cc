#include "sim/joint_experiment.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include <fmt/format.h>

#include "core/errors.h"

namespace driveid {
namespace {

using State = std::array<double, 4>;  // theta_m, theta_m', theta_l, theta_l' (link side)

// The forces on the motor and the link but their Coulomb friction [N m].
std::array<double, 2> Forces(const JointParameters& p, const State& x, double tau_m) {
  const double spring = p.stiffness * (x[0] - x[2]) + p.damping * (x[1] - x[3]);
  const double gravity = p.gravity_cos * std::cos(x[2]) + p.gravity_sin * std::sin(x[2]);
  return {tau_m - spring - p.motor_viscous * x[1] - p.offset, spring - p.link_viscous * x[3] - gravity};
}

// The state's derivative with the Coulomb forces the sub-step chose: a body
// held at rest gets exactly the force that holds it, so its acceleration is
// exactly 0 (a force recovered from an acceleration times the inertia was
// off in the last bit, and the body crept).
State Derivative(const JointParameters& p, const State& x, double tau_m, double coulomb_m, double coulomb_l) {
  const std::array<double, 2> force = Forces(p, x, tau_m);
  return {x[1], (force[0] - coulomb_m) / p.motor_inertia, x[3], (force[1] - coulomb_l) / p.link_inertia};
}

std::vector<double> Excitation(const JointExperiment& e, std::size_t samples) {
  if (e.excitation == "reference") {
    std::vector<double> r(samples);
    for (std::size_t i = 0; i < samples; ++i) r[i] = e.reference[i % e.reference.size()];
    return r;
  }
  const auto period = static_cast<std::size_t>(std::llround(e.period * e.rate));
  std::vector<double> one(period, 0.0);
  if (e.excitation == "multisine") {
    const int first = std::max(1, static_cast<int>(std::ceil(e.f_low * e.period)));
    const int last = static_cast<int>(std::floor(e.f_high * e.period));
    if (last < first) throw OptionError(fmt::format("‹band› {},{}: no line of the {} s period in it", e.f_low, e.f_high, e.period));
    const int lines = last - first + 1;
    for (std::size_t i = 0; i < period; ++i) {
      for (int l = first; l <= last; ++l) {
        const double phase = -M_PI * (l - first) * (l - first + 1) / lines;  // Schroeder: low crest factor
        one[i] += std::cos(2.0 * M_PI * l * static_cast<double>(i) / static_cast<double>(period) + phase);
      }
    }
  } else if (e.excitation == "chirp") {
    for (std::size_t i = 0; i < period; ++i) {
      const double t = static_cast<double>(i) / e.rate;
      one[i] = std::sin(2.0 * M_PI * (e.f_low * t + 0.5 * (e.f_high - e.f_low) / e.period * t * t));
    }
  } else {  // prbs: a 15-bit maximal-length sequence, a bit held for rate / (2.5 f_high) samples
    const auto hold = static_cast<std::size_t>(std::max(1.0, std::floor(e.rate / (2.5 * e.f_high))));
    unsigned state = 0x7fffu;
    for (std::size_t i = 0; i < period; i += hold) {
      const unsigned bit = ((state >> 14) ^ (state >> 13)) & 1u;
      state = ((state << 1) | bit) & 0x7fffu;
      for (std::size_t j = i; j < std::min(period, i + hold); ++j) one[j] = bit ? 1.0 : -1.0;
    }
  }
  double power = 0.0;
  for (double v : one) power += v * v;
  const double scale = power > 0.0 ? e.amplitude / std::sqrt(power / static_cast<double>(period)) : 0.0;
  std::vector<double> r(samples);
  for (std::size_t i = 0; i < samples; ++i) r[i] = scale * one[i % period];
  return r;
}

}  // namespace

JointExperimentLog SimulateJointExperiment(const JointParameters& p, double n, const JointExperiment& e) {
  const auto finite_above = [](double v, double lo) { return std::isfinite(v) && v > lo; };
  const bool given = e.excitation == "reference";
  if (e.excitation != "multisine" && e.excitation != "chirp" && e.excitation != "prbs" && !given) {
    throw OptionError(fmt::format("‹excitation› {}: multisine, chirp or prbs", e.excitation));
  }
  if (given && (e.reference.empty() || !std::all_of(e.reference.begin(), e.reference.end(),
                                                    [](double v) { return std::isfinite(v); }))) {
    throw InputError("‹reference›: an excitation needs finite torque samples");
  }
  if (!finite_above(e.rate, 0.0) || e.rate > 1e6) throw OptionError(fmt::format("‹rate› {}: (0, 1e6] Hz", e.rate));
  if (!finite_above(e.duration, 0.0) || e.duration * e.rate > 5e6) {
    throw OptionError(fmt::format("‹duration› {} s: positive, at most 5e6 samples at ‹rate›", e.duration));
  }
  if (!given && (!finite_above(e.period, 0.0) || e.period * e.rate < 16 || e.period > e.duration)) {
    throw OptionError(fmt::format("‹period› {} s: at least 16 samples and at most ‹duration›", e.period));
  }
  if (!given && (!(e.f_low >= 0.0) || !(e.f_high > e.f_low) || !(e.f_high <= 0.5 * e.rate))) {
    throw OptionError(fmt::format("‹band› {},{}: 0 <= LO < HI <= rate/2", e.f_low, e.f_high));
  }
  if (!std::isfinite(e.amplitude) || !std::isfinite(e.kp) || !std::isfinite(e.ki) || !(e.noise >= 0.0) ||
      !std::isfinite(e.noise)) {
    throw OptionError("‹amplitude›, ‹kp›, ‹ki› and ‹noise› must be finite (‹noise› >= 0)");
  }
  if (!finite_above(p.motor_inertia, 0.0) || !finite_above(p.link_inertia, 0.0) || !(p.stiffness >= 0.0)) {
    throw InputError("joint: motor_inertia and link_inertia > 0 and stiffness >= 0 are needed for the simulation");
  }
  const auto samples = static_cast<std::size_t>(std::llround(e.duration * e.rate));
  const std::vector<double> r = Excitation(e, samples);
  std::mt19937_64 rng(e.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double dt = 1.0 / e.rate, h = dt / e.substeps;
  JointExperimentLog log;
  State x{0.0, 0.0, 0.0, 0.0};
  double integral = 0.0;
  for (std::size_t i = 0; i < samples; ++i) {
    const double speed = n * x[1] + e.noise * normal(rng);
    integral += speed * dt;
    const double tau = r[i] - e.kp * speed - e.ki * integral;
    log.t.push_back(static_cast<double>(i) * dt);
    log.tau.push_back(tau);
    log.q_motor.push_back(n * x[0]);
    log.qd_motor.push_back(speed);
    log.q_link.push_back(x[2]);
    log.r.push_back(r[i]);
    const double tau_m = n * tau;
    for (int s = 0; s < e.substeps; ++s) {
      // Coulomb forces of this sub-step: kinetic while moving, else what
      // holds the mass (within the Coulomb level) or the level itself.
      const std::array<double, 2> force = Forces(p, x, tau_m);  // what would move each body
      const auto coulomb = [](double rate, double needed, double level) {
        if (rate != 0.0) return level * (rate > 0.0 ? 1.0 : -1.0);
        return std::abs(needed) <= level ? needed : level * (needed > 0.0 ? 1.0 : -1.0);
      };
      const double cm = coulomb(x[1], force[0], p.motor_coulomb);
      const double cl = coulomb(x[3], force[1], p.link_coulomb);
      const auto f = [&](const State& y) { return Derivative(p, y, tau_m, cm, cl); };
      const State k1 = f(x);
      State y;
      for (int j = 0; j < 4; ++j) y[j] = x[j] + 0.5 * h * k1[j];
      const State k2 = f(y);
      for (int j = 0; j < 4; ++j) y[j] = x[j] + 0.5 * h * k2[j];
      const State k3 = f(y);
      for (int j = 0; j < 4; ++j) y[j] = x[j] + h * k3[j];
      const State k4 = f(y);
      const State before = x;
      for (int j = 0; j < 4; ++j) x[j] += h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
      // A speed that crosses zero under Coulomb friction stops there (it
      // moves on next sub-step only if the forces exceed the level).
      if (p.motor_coulomb > 0.0 && before[1] != 0.0 && before[1] * x[1] <= 0.0) x[1] = 0.0;
      if (p.link_coulomb > 0.0 && before[3] != 0.0 && before[3] * x[3] <= 0.0) x[3] = 0.0;
    }
  }
  return log;
}

}  // namespace driveid
