#include "support/reference_scope_trace.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <random>

namespace driveid::testing {
namespace {

using State = std::array<double, 4>;  // th_m, th_m', th_l, th_l'

State Rates(const ScopeAxis& a, const State& x, double drive) {
  const double spring = a.stiffness * (x[0] - x[2]) + a.damping * (x[1] - x[3]);
  const double friction = a.motor_viscous * x[1] + a.motor_coulomb * std::tanh(x[1] / a.coulomb_speed);
  return {x[1], (drive - spring - friction) / a.motor_inertia, x[3], (spring - a.link_viscous * x[3]) / a.link_inertia};
}

State Step(const ScopeAxis& a, const State& x, double drive, double h) {
  const auto at = [](const State& s, const State& d, double c) {
    return State{s[0] + c * d[0], s[1] + c * d[1], s[2] + c * d[2], s[3] + c * d[3]};
  };
  const State k1 = Rates(a, x, drive), k2 = Rates(a, at(x, k1, h / 2), drive), k3 = Rates(a, at(x, k2, h / 2), drive),
              k4 = Rates(a, at(x, k3, h), drive);
  State out;
  for (int i = 0; i < 4; ++i) out[i] = x[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
  return out;
}

// Position and speed of a trapezoid move of `stroke` after `t` seconds.
std::array<double, 2> Trapezoid(double t, double stroke, double v_max, double a_max) {
  const double sign = stroke < 0.0 ? -1.0 : 1.0, s = std::abs(stroke);
  double ramp = v_max / a_max, cruise = s / v_max - ramp;
  if (cruise < 0.0) {  // a triangle
    ramp = std::sqrt(s / a_max);
    cruise = 0.0;
  }
  const double v = a_max * ramp;
  if (t <= 0.0) return {0.0, 0.0};
  if (t < ramp) return {sign * 0.5 * a_max * t * t, sign * a_max * t};
  if (t < ramp + cruise) return {sign * (0.5 * v * ramp + v * (t - ramp)), sign * v};
  const double td = t - ramp - cruise;
  if (td < ramp) return {sign * (0.5 * v * ramp + v * cruise + v * td - 0.5 * a_max * td * td), sign * (v - a_max * td)};
  return {stroke, 0.0};
}

}  // namespace

std::string SimulateScopeTrace(const ScopeAxis& axis, const ScopeSettings& c) {
  std::mt19937_64 rng(c.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double dt = 1.0 / c.rate, h = dt / c.substeps;
  const double motor_step = 2.0 * M_PI / c.motor_counts, link_step = 2.0 * M_PI / c.link_counts;
  const double n = axis.gear_ratio;
  // One move plus dwell, alternating direction.
  const double ramp = c.max_speed / c.acceleration;
  const double move_time = std::max(2.0 * std::sqrt(c.move / c.acceleration), c.move / c.max_speed + ramp);
  const double cycle = move_time + c.dwell;
  const double filter = 1.0 - std::exp(-2.0 * M_PI * c.speed_filter_hz * dt);
  std::string out = "time_ms,enc_motor,enc_link,torque_permille\n";
  State x{0.0, 0.0, 0.0, 0.0};
  double speed = 0.0, integral = 0.0, previous_counts = 0.0, applied = 0.0;
  const auto samples = static_cast<long>(std::llround(c.duration * c.rate));
  char line[128];
  for (long i = 0; i < samples; ++i) {
    const double t = static_cast<double>(i) * dt;
    const long k = static_cast<long>(std::floor(t / cycle));
    const double base = (k % 2 == 0) ? 0.0 : c.move;  // at rest at 0 or at the stroke
    const auto [p, v] = Trapezoid(t - static_cast<double>(k) * cycle - c.dwell, k % 2 == 0 ? c.move : -c.move, c.max_speed, c.acceleration);
    const double target = base + p;
    const double counts_m = std::round(n * x[0] / motor_step), counts_l = std::round(x[2] / link_step);
    const double q_motor = counts_m * motor_step;
    speed += filter * ((i == 0 ? 0.0 : (counts_m - previous_counts) * motor_step / dt) - speed);
    previous_counts = counts_m;
    const double speed_command = v + c.kp_position * (target - q_motor);
    const double error = speed_command - speed;
    integral += c.ki_speed * error * dt;
    const double command = c.kp_speed * error + integral;
    const double logged = applied + c.torque_noise * normal(rng);
    std::snprintf(line, sizeof line, "%.4f,%.0f,%.0f,%.0f\n", 1e3 * t, counts_m, counts_l,
                  std::round(1000.0 * logged / c.rated_torque));
    out += line;
    for (int s = 0; s < c.substeps; ++s) x = Step(axis, x, n * applied, h);
    applied = command;  // applied one sample late
  }
  return out;
}

}  // namespace driveid::testing
