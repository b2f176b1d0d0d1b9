#include "fit/robot/robot_fit.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/name_list.h"
#include "core/option_check.h"
#include "core/order_statistics.h"
#include "fit/core/linear_regression.h"
#include "logs/csv_log.h"
#include "signal/local_polynomial.h"

namespace driveid {
namespace {

// The regressor columns in the order of the robot fit's rows of the table:
// Theta, m_c, d_g.
const ParameterRow<PlanarRobotSection, PlanarRobotParameters>& Column(std::size_t j) {
  static const auto rows = [] {
    std::vector<const ParameterRow<PlanarRobotSection, PlanarRobotParameters>*> out;
    for (const auto& row : PlanarRobotParameterTable()) {
      if (row.spec.InFit("robot")) out.push_back(&row);
    }
    return out;
  }();
  return *rows.at(j);
}

// Kinematic quantities of one sample.
struct Sample {
  Vector3 theta, rate, acceleration;
  Vector2 position, velocity, acceleration_xy;
  Matrix23 g;
};

// Refuses a log whose joint angles do not close the robot at some sample
// (wrong l or a, angles in degrees, swapped columns, another robot): names the
// first such line.
void CheckClosure(const PlanarRobotParameters& robot, const RobotLog& log) {
  const double a = robot.base_distance;
  Vector2 guess = {0.5 * a, a / (2.0 * std::sqrt(3.0))};
  for (std::size_t k = 0; k < log.time.size(); ++k) {
    const Vector3 theta{log.angle[0][k], log.angle[1][k], log.angle[2][k]};
    const Vector2 c = CalcForwardKinematics(robot, theta, guess);
    const ClosureCheck check = CalcClosure(robot, theta, c);
    const std::string where = k < log.line_numbers.size() ? fmt::format("{}:{}", log.path, log.line_numbers[k])
                                                          : fmt::format("{}: sample {}", log.path, k + 1);
    if (!(check.length_error <= kClosureTolerance)) {
      throw InputError(fmt::format(
          "{}: the joint angles do not close the robot (a leg misses the centre joint by {:.3g} % of l = {} m; "
          "tolerance {} %): check base_distance and l in ‹params›, that the angles are in radians at the gear "
          "output, and the column order (docs/models.md#planar-robot)",
          where, 100.0 * check.length_error, robot.link_length, 100.0 * kClosureTolerance));
    }
    if (check.wrong_elbow != 0) {
      throw InputError(fmt::format("{}: leg {}'s elbow is on the other side of the one given by elbow in ‹params›",
                                   where, check.wrong_elbow));
    }
    guess = c;
  }
}

// Differentiates a log; returns the valid samples and their indices.
std::vector<std::pair<std::size_t, Sample>> Kinematics(const PlanarRobotParameters& robot, const RobotLog& log,
                                                       double half_window) {
  std::array<SignalDerivatives, 3> joints;
  for (std::size_t i = 0; i < 3; ++i) joints[i] = EstimateDerivatives(log.time, log.angle[i], half_window);
  const std::size_t n = log.time.size();
  std::vector<double> x(n), y(n);
  const double a = robot.base_distance;
  Vector2 guess = {0.5 * a, a / (2.0 * std::sqrt(3.0))};
  for (std::size_t k = 0; k < n; ++k) {
    const Vector2 c = CalcForwardKinematics(robot, {joints[0].value[k], joints[1].value[k], joints[2].value[k]}, guess);
    x[k] = c[0];
    y[k] = c[1];
    guess = c;
  }
  const SignalDerivatives dx = EstimateDerivatives(log.time, x, half_window);
  const SignalDerivatives dy = EstimateDerivatives(log.time, y, half_window);
  std::vector<std::pair<std::size_t, Sample>> out;
  out.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (!(joints[0].valid[k] && joints[1].valid[k] && joints[2].valid[k] && dx.valid[k] && dy.valid[k])) continue;
    Sample s;
    for (std::size_t i = 0; i < 3; ++i) {
      s.theta[i] = joints[i].value[k];
      s.rate[i] = joints[i].rate[k];
      s.acceleration[i] = joints[i].acceleration[k];
    }
    s.position = {x[k], y[k]};
    s.velocity = {dx.rate[k], dy.rate[k]};
    s.acceleration_xy = {dx.acceleration[k], dy.acceleration[k]};
    s.g = CalcTransposedInverseJacobian(robot, s.position, s.theta);
    out.emplace_back(k, s);
  }
  return out;
}

}  // namespace



namespace {

// Jumps (steps of the commanded acceleration) cannot be followed by any
// smooth differentiator: find them where a current leaves its local fit by
// more than 4 robust standard deviations, and mark every sample whose
// window reaches one.
std::vector<char> NearCurrentJumps(const RobotLog& log, const std::array<std::vector<double>, 3>& current,
                                   double half_window) {
  std::vector<char> near_jump(log.time.size(), 0);
  for (std::size_t i = 0; i < 3; ++i) {
    std::vector<double> deviation(log.time.size());
    for (std::size_t k = 0; k < deviation.size(); ++k) deviation[k] = std::abs(log.current[i][k] - current[i][k]);
    const double sigma = RobustStd(deviation);
    for (std::size_t k = 0; k < deviation.size(); ++k) {
      if (!(deviation[k] > 4.0 * sigma) || sigma <= 0.0) continue;
      // Mark the window around k (time is increasing: scan outwards).
      for (std::size_t m = k; m-- > 0 && log.time[k] - log.time[m] <= half_window;) near_jump[m] = 1;
      for (std::size_t m = k; m < log.time.size() && log.time[m] - log.time[k] <= half_window; ++m) near_jump[m] = 1;
    }
  }
  return near_jump;
}

// The measured currents and the model's parts (Fig. 7 decomposition) at the
// kinematics' samples of one log, with the fitted parameters.
RobotCurrentPrediction PredictCurrents(const RobotLog& log, const std::vector<std::pair<std::size_t, Sample>>& kinematics,
                                       const PlanarRobotParameters& r) {
  const double n_g = r.gear_ratio, scale = 1.0 / (n_g * r.torque_constant);
  RobotCurrentPrediction prediction;
  for (const auto& [k, s] : kinematics) {
    const Matrix23 g_rate = CalcTransposedInverseJacobianRate(r, s.position, s.theta, s.velocity);
    const Vector3 centre = ApplyPseudoInverse(s.g, {r.center_mass * s.acceleration_xy[0], r.center_mass * s.acceleration_xy[1]});
    // G+ G i: the part of the measured current that moves the robot.
    Vector2 projected = Vector2::Zero();
    for (std::size_t i = 0; i < 3; ++i) {
      projected[0] += s.g(0, i) * log.current[i][k];
      projected[1] += s.g(1, i) * log.current[i][k];
    }
    const Vector3 motion = ApplyPseudoInverse(s.g, projected);
    // Centrifugal/Coriolis: Theta dG' x' has a null-space part; the motors
    // share the Cartesian force G Theta dG' x' by the minimum norm, G+ G.
    Vector3 coriolis_joint = Vector3::Zero();
    Vector2 coriolis_force = Vector2::Zero();
    for (std::size_t i = 0; i < 3; ++i) {
      coriolis_joint[i] = r.output_inertia * (g_rate(0, i) * s.velocity[0] + g_rate(1, i) * s.velocity[1]);
      coriolis_force[0] += s.g(0, i) * coriolis_joint[i];
      coriolis_force[1] += s.g(1, i) * coriolis_joint[i];
    }
    const Vector3 coriolis_motion = ApplyPseudoInverse(s.g, coriolis_force);
    prediction.time.push_back(log.time[k]);
    for (std::size_t i = 0; i < 3; ++i) {
      const double inertia = (r.output_inertia * (s.g(0, i) * s.acceleration_xy[0] + s.g(1, i) * s.acceleration_xy[1]) +
                              centre[i]) * scale;
      const double coriolis = coriolis_motion[i] * scale;
      const double friction = n_g * n_g * r.viscous_friction * s.rate[i] * scale;
      prediction.measured[i].push_back(log.current[i][k]);
      prediction.measured_motion[i].push_back(motion[i]);
      prediction.inertia[i].push_back(inertia);
      prediction.coriolis[i].push_back(coriolis);
      prediction.friction[i].push_back(friction);
      prediction.total[i].push_back(inertia + coriolis + friction);
    }
  }
  return prediction;
}

}  // namespace

bool RobotFitOptions::IsValid(std::string* error) const {
  if (half_window > 0.0 && std::isfinite(half_window)) return true;
  *error = ViolatedConstraint("‹window›", half_window, "> 0 s");
  return false;
}

RobotFitOutput FitRobot(const std::vector<RobotLog>& logs, const PlanarRobotParameters& start,
                        const RobotFitOptions& options) {
  if (logs.empty()) throw OptionError("no logs given");
  CheckFreeNames(PlanarRobotParameterTable(), "robot", options.free);
  RequireValid(options);
  if (!(start.torque_constant > 0.0)) throw InputError("‹params›: planar_robot.k_t is needed (currents to torques)");
  std::vector<FitParameter> parameters;
  std::vector<std::string> column_names;
  std::map<std::string, double> fixed;
  for (int j = 0; j < 3; ++j) {
    const double value = start.*(Column(j).in_model);
    column_names.push_back(Column(j).spec.key);
    fixed[Column(j).spec.key] = value;
    if (!Contains(options.free, Column(j).spec.key)) continue;
    parameters.push_back({Column(j).spec.key, value > 0.0 ? value : 0.0, 0.0, value > 0.0 ? value : 1.0});
  }
  const std::size_t p = parameters.size();
  const double n_g = start.gear_ratio, k_t = start.torque_constant;

  std::vector<std::vector<std::pair<std::size_t, Sample>>> kinematics;
  // Per sample and Cartesian component: [G theta'', x'', n_g^2 G theta'] against n_g G tau.
  LinearRegression regression(column_names);
  for (const auto& log : logs) {
    if (log.time.size() < kMinRobotLogSamples) throw InputError(fmt::format("{}: {} samples: too few", log.path, log.time.size()));
    CheckClosure(start, log);
    try {
      kinematics.push_back(Kinematics(start, log, options.half_window));
    } catch (const std::domain_error& e) {
      throw InputError(fmt::format("{}: joint angles outside the workspace: {}", log.path, e.what()));
    }
    // Parallel filtering: the currents pass the same zero-phase local fit as
    // the angles, so that both sides of the equation see the same bandwidth
    // (the trapezoid's acceleration jumps otherwise bias Theta).
    std::array<std::vector<double>, 3> current;
    for (std::size_t i = 0; i < 3; ++i) current[i] = EstimateDerivatives(log.time, log.current[i], options.half_window).value;
    const std::vector<char> near_jump = NearCurrentJumps(log, current, options.half_window);
    // Decimation to the filter band: smoothed rows are correlated over the
    // window, so keep about one row per half window (honest standard errors).
    const double mean_step = (log.time.back() - log.time.front()) / static_cast<double>(log.time.size() - 1);
    const std::size_t stride = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(options.half_window / mean_step)));
    for (int component = 0; component < 2; ++component) {
      regression.BeginChannel(log.path + (component == 0 ? ":force_x" : ":force_y"));
      std::size_t counter = 0;
      for (const auto& [k, s] : kinematics.back()) {
        if (near_jump[k] || counter++ % stride != 0) continue;
        double projected_torque = 0.0, projected_acceleration = 0.0, projected_rate = 0.0;
        for (int i = 0; i < 3; ++i) {
          const double g = s.g(component, i);
          projected_torque += g * k_t * current[static_cast<std::size_t>(i)][k];
          projected_acceleration += g * s.acceleration[i];
          projected_rate += g * s.rate[i];
        }
        regression.AddRow({projected_acceleration, s.acceleration_xy[component],
                           n_g * n_g * projected_rate},
                          n_g * projected_torque);
      }
    }
  }
  if (regression.rows() <= p) {
    throw IdentificationError("too few usable samples (logs shorter than the differentiator window)");
  }
  FitOptions fit_options = options.fit;
  if (!fit_options.advice) {
    fit_options.advice = [](const std::vector<std::string>&) -> std::string {
      return "the trajectory must accelerate and move at speed in both directions (e.g. simulate robot's triangle)";
    };
  }
  RobotFitOutput out;
  out.fit = regression.Fit(parameters, fixed, fit_options);
  out.params = start;
  for (const auto& e : out.fit.estimates) out.params.*(FindParameter(PlanarRobotParameterTable(), e.name)->in_model) = e.value;

  // Current prediction with the fitted parameters (Fig. 7 decomposition).
  for (std::size_t l = 0; l < logs.size(); ++l) out.predictions.push_back(PredictCurrents(logs[l], kinematics[l], out.params));
  return out;
}

}  // namespace driveid
