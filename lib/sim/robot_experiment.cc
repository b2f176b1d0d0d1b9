#include "sim/robot_experiment.h"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "core/option_check.h"

#include "sim/noise.h"

namespace driveid {
namespace {

// Trapezoidal (or triangular) rest-to-rest profile along a segment of `length`.
struct Profile {
  double accelerate, cruise, peak;  // phase durations [s] and peak speed
};

Profile MakeProfile(double length, double acceleration, double speed) {
  const double ramp_distance = speed * speed / acceleration;  // accelerate + decelerate
  if (ramp_distance >= length) {
    const double peak = std::sqrt(length * acceleration);
    return {peak / acceleration, 0.0, peak};
  }
  return {speed / acceleration, (length - ramp_distance) / speed, speed};
}

// Distance, speed and acceleration along the segment at time t in [0, move].
void Along(const Profile& p, double a, double t, double* s, double* v, double* acc) {
  const double t1 = p.accelerate, t2 = p.accelerate + p.cruise, t3 = t2 + p.accelerate;
  if (t < t1) {
    *s = 0.5 * a * t * t, *v = a * t, *acc = a;
  } else if (t < t2) {
    *s = 0.5 * a * t1 * t1 + p.peak * (t - t1), *v = p.peak, *acc = 0.0;
  } else if (t < t3) {
    const double r = t3 - t;
    const double total = a * t1 * t1 + p.peak * p.cruise;
    *s = total - 0.5 * a * r * r, *v = a * r, *acc = -a;
  } else {
    *s = a * t1 * t1 + p.peak * p.cruise, *v = 0.0, *acc = 0.0;
  }
}

std::array<Vector2, 3> Corners(const PlanarRobotParameters& robot, double side) {
  const double a = robot.base_distance;
  const Vector2 centre = {0.5 * a, a / (2.0 * std::sqrt(3.0))};
  const double radius = side / std::sqrt(3.0);
  std::array<Vector2, 3> corners{};
  for (int k = 0; k < 3; ++k) {
    const double angle = M_PI / 2.0 + k * 2.0 * M_PI / 3.0;
    corners[static_cast<std::size_t>(k)] = {centre[0] + radius * std::cos(angle), centre[1] + radius * std::sin(angle)};
  }
  return corners;
}

}  // namespace

double CalcTriangleDuration(const RobotExperiment& e) {
  const Profile p = MakeProfile(e.side, e.acceleration, e.speed);
  return e.loops * 3.0 * (2.0 * p.accelerate + p.cruise + e.dwell) + e.dwell;
}

PathSample CalcTrianglePath(const PlanarRobotParameters& robot, const RobotExperiment& e, double time) {
  const auto corners = Corners(robot, e.side);
  const Profile p = MakeProfile(e.side, e.acceleration, e.speed);
  const double move = 2.0 * p.accelerate + p.cruise;
  const double edge_time = e.dwell + move;  // dwell first, then move
  const int edges = 3 * e.loops;
  int edge = static_cast<int>(std::floor(time / edge_time));
  double local = time - edge * edge_time;
  if (edge >= edges) {
    edge = edges - 1;
    local = edge_time;
  }
  const Vector2 from = corners[static_cast<std::size_t>(edge % 3)];
  const Vector2 to = corners[static_cast<std::size_t>((edge + 1) % 3)];
  const Vector2 unit = {(to[0] - from[0]) / e.side, (to[1] - from[1]) / e.side};
  double s = 0.0, v = 0.0, acc = 0.0;
  if (local > e.dwell) Along(p, e.acceleration, local - e.dwell, &s, &v, &acc);
  return {{from[0] + s * unit[0], from[1] + s * unit[1]}, {v * unit[0], v * unit[1]}, {acc * unit[0], acc * unit[1]}};
}

RobotLog SimulateRobotExperiment(const PlanarRobotParameters& robot, const RobotExperiment& e) {
  RequireOption(e.side > 0.0 && std::isfinite(e.side), "‹side›", e.side, "side > 0 m");
  RequireOption(e.acceleration > 0.0 && std::isfinite(e.acceleration), "‹acceleration›", e.acceleration, "> 0 m/s^2");
  RequireOption(e.speed > 0.0 && std::isfinite(e.speed), "‹speed›", e.speed, "> 0 m/s");
  RequireOption(e.dwell >= 0.0 && std::isfinite(e.dwell), "‹dwell›", e.dwell, ">= 0 s");
  RequireOption(e.loops >= 1 && e.loops <= 10000, "‹loops›", e.loops, "1 <= loops <= 10000");
  RequireOption(e.rate > 0.0 && std::isfinite(e.rate), "‹rate›", e.rate, "> 0 Hz");
  RequireOption(e.current_noise >= 0.0 && std::isfinite(e.current_noise), "‹noise›", e.current_noise, ">= 0 A");
  RequireOption(std::isfinite(e.prestress), "‹prestress›", e.prestress, "finite");
  const double duration = CalcTriangleDuration(e);
  RequireSampleCount(std::round(duration * e.rate) + 1, kMinRobotLogSamples,
                     fmt::format("‹rate› {} with ‹loops› {} (a {:.4g} s triangle program)", e.rate, e.loops, duration));
  GaussianNoise noise(e.seed);
  const double quantum = 2.0 * M_PI / (e.encoder_counts * robot.gear_ratio);
  RobotLog log;
  log.path = "simulated";
  const long samples = std::lround(duration * e.rate) + 1;
  for (long k = 0; k < samples; ++k) {
    const double t = static_cast<double>(k) / e.rate;
    const PathSample path = CalcTrianglePath(robot, e, t);
    const Vector3 theta = CalcInverseKinematics(robot, path.position);
    const Matrix23 g = CalcTransposedInverseJacobian(robot, path.position, theta);
    const Matrix23 g_rate = CalcTransposedInverseJacobianRate(robot, path.position, theta, path.velocity);
    // theta' = G' x', theta'' = dG' x' + G' x''.
    Vector3 rate{}, acceleration{};
    for (std::size_t i = 0; i < 3; ++i) {
      rate[i] = g(0, i) * path.velocity[0] + g(1, i) * path.velocity[1];
      acceleration[i] = g_rate(0, i) * path.velocity[0] + g_rate(1, i) * path.velocity[1] + g(0, i) * path.acceleration[0] +
                        g(1, i) * path.acceleration[1];
    }
    const Vector3 centre_force = ApplyPseudoInverse(
        g, {robot.center_mass * path.acceleration[0], robot.center_mass * path.acceleration[1]});
    const Vector3 null = CalcNullSpace(g);
    log.time.push_back(t);
    for (std::size_t i = 0; i < 3; ++i) {
      // n_g tau_motor = Theta theta'' + n_g^2 d_g theta' + G+ m_c x'' + prestress n.
      const double output_torque = robot.output_inertia * acceleration[i] +
                                   robot.gear_ratio * robot.gear_ratio * robot.viscous_friction * rate[i] +
                                   centre_force[i] + e.prestress * null[i];
      const double current = output_torque / robot.gear_ratio / robot.torque_constant;
      log.angle[i].push_back(std::floor(theta[i] / quantum) * quantum);
      log.current[i].push_back(current + (e.current_noise > 0.0 ? noise.Next(e.current_noise) : 0.0));
    }
  }
  return log;
}


}  // namespace driveid
