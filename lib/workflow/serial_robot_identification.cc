#include "workflow/serial_robot_identification.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"
#include "models/serial_dynamics.h"

namespace driveid {

bool SerialRobotIdentificationOptions::IsValid(std::string* error) const {
  return OptionCheck(error).Nested(fit).Require(prior_weight > 0.0 && std::isfinite(prior_weight), "‹prior_weight›",
                                                prior_weight, "weight > 0");
}

namespace {

// A joint whose torque the model explains this poorly is named in a warning:
// an unmodelled effect (a cable, a payload, elasticity) or a wrong URDF.
constexpr double kPoorRelativeErrorPercent = 30.0;
// A consistent estimate this many std from the unconstrained one: the
// constraint binds, which the data alone would not do by chance.
constexpr double kBindingShift = 2.0;

// The consistent parameters replace the estimates; each interval moves with
// its estimate (its width is the data's).
void UseConsistent(SerialRobotIdentification& run) {
  FitResult& fit = run.result.fit;
  const ConsistentParameters& c = run.consistent;
  if (!c.unknown_bodies.empty()) {
    fit.warnings.push_back(fmt::format(
        "physical consistency: the URDF gives {} of the bodies no mass (no <inertial>); their consistent values start "
        "from 1 kg at the joint under a prior 100 x weaker than a URDF's: the base parameters (what the logs "
        "determine) are fitted, but the bodies themselves are one of many that fit, not for a simulator without a "
        "check (docs/models.md#physical-consistency)",
        c.unknown_bodies.size()));
  }
  if (!c.converged) {
    fit.warnings.push_back(fmt::format("physical consistency: the consistent fit did not converge ({}); the values are "
                                       "its last iterate (docs/models.md#physical-consistency)",
                                       c.termination));
  }
  if (c.largest_shift > kBindingShift) {
    fit.warnings.push_back(fmt::format(
        "physical consistency: the unconstrained estimates lie outside the physically consistent set (chi^2 {:.3g}); "
        "the consistent ones reported differ by up to {:.2g} std ({}): a model term the robot has and the model lacks, "
        "a wrong URDF structure, or a torque column in other units (docs/models.md#physical-consistency)",
        c.chi2, c.largest_shift, c.largest_shift_name));
  } else {
    fit.notes.push_back(fmt::format("physical consistency: the consistent parameters are within {:.2g} std of the "
                                    "unconstrained estimates (chi^2 {:.3g}); they are the ones reported",
                                    c.largest_shift, c.chi2));
  }
  for (std::size_t k = 0; k < fit.estimates.size(); ++k) {
    ParameterEstimate& e = fit.estimates[k];
    const double shift = c.base[run.result.free[k]] - e.value;
    e.value += shift;
    e.ci95_low += shift;
    e.ci95_high += shift;
  }
}

UrdfRobot WithViscousPerDirection(UrdfRobot robot, const std::vector<std::string>& joints) {
  for (const std::string& name : joints) {
    bool found = false;
    for (SerialJoint& j : robot.robot.joints) {
      if (name == "all" || j.name == name) j.viscous_per_direction = found = true;
    }
    if (!found) {
      std::vector<std::string> names;
      for (const SerialJoint& j : robot.robot.joints) names.push_back(j.name);
      throw OptionError(fmt::format("‹per_direction›: the robot has no joint '{}' (its joints: {}, or all)", name,
                                    fmt::join(names, ", ")));
    }
  }
  return robot;
}

// Viscous friction per direction, b+- = viscous +- viscous_asymmetry, of
// the joints that ask for it where both are base parameters of their own.
std::string PerDirectionLines(const SerialRobot& robot, const SerialRobotFitOutput& r) {
  const auto find = [&](const std::string& name) {
    for (std::size_t c = 0; c < r.free.size(); ++c) {
      if (r.fit.estimates[c].name == name && r.base.combination[r.free[c]].size() == 1) return c;
    }
    return r.free.size();
  };
  std::string out;
  const std::size_t p = r.free.size();
  for (const SerialJoint& j : robot.joints) {
    const std::size_t b = find("viscous_" + j.name), d = find("viscous_asymmetry_" + j.name);
    if (!j.viscous_per_direction || b == p || d == p) continue;
    const double vb = r.fit.covariance[b * p + b], vd = r.fit.covariance[d * p + d], cbd = r.fit.covariance[b * p + d];
    for (const int sign : {1, -1}) {
      out += fmt::format("{:<56} {:>12.5g} {:>10.3g}\n", fmt::format("viscous_{}_{} (viscous {} viscous_asymmetry)",
                                                                      sign > 0 ? "pos" : "neg", j.name, sign > 0 ? "+" : "-"),
                         r.fit.estimates[b].value + sign * r.fit.estimates[d].value,
                         std::sqrt(std::max(0.0, vb + vd + 2.0 * sign * cbd)));
    }
  }
  return out;
}

std::string Summary(const SerialRobot& robot, const SerialRobotIdentification& run) {
  const SerialRobotFitOutput& r = run.result;
  std::string out = fmt::format("{} base parameters from {} samples; condition number of the column-normalised base "
                                "regressor {:.3g}\n",
                                r.base.base.size(), r.samples, r.condition_number);
  out += fmt::format("{:<24} {:>12} {:>10} {:>10}\n", "joint", "rmse", "fit %", "rel. err %");
  for (const auto& j : r.joints) {
    out += fmt::format("{:<24} {:>12.4g} {:>10.2f} {:>10.2f}\n", j.joint, j.rmse, j.fit_percent, j.relative_error_percent);
  }
  out += fmt::format("{:<56} {:>12} {:>10} {:>26}\n", "base parameter", "value", "std", "ci95");
  for (std::size_t c = 0; c < r.fit.estimates.size(); ++c) {
    const ParameterEstimate& e = r.fit.estimates[c];
    out += fmt::format("{:<56} {:>12.5g} {:>10.3g} [{:.5g}, {:.5g}]\n", r.base.names[r.free[c]], e.value,
                       e.standard_error, e.ci95_low, e.ci95_high);
  }
  for (std::size_t k = 0; k < r.held.size(); ++k) {
    if (!std::isnan(r.held[k])) out += fmt::format("{:<56} {:>12.5g} {:>10} (the URDF's)\n", r.base.names[k], r.held[k], "held");
  }
  out += PerDirectionLines(robot, r);
  std::vector<std::string> names;
  for (std::size_t c : r.base.never_moved) {
    // A drive term the joint does not ask for is no parameter of the model.
    const std::size_t within = c % kSerialColumnsPerJoint;
    if (within >= kInertialParameters &&
        !SerialDriveTerms()[within - kInertialParameters]->Asked(robot.joints[c / kSerialColumnsPerJoint])) {
      continue;
    }
    names.push_back(r.parameter_names[c]);
  }
  if (!names.empty()) {
    out += fmt::format("never reach a joint torque (left out): {}\n", fmt::join(names, ", "));
  }
  for (const std::string& note : r.fit.notes) out += "note: " + note + "\n";
  return out;
}

}  // namespace

SerialRobotIdentification IdentifySerialRobot(const UrdfRobot& urdf, const std::string& urdf_path,
                                              const std::string& urdf_sha256, const std::vector<SerialRobotLog>& logs,
                                              const SerialRobotIdentificationOptions& options) {
  RequireValid(options);
  const UrdfRobot robot = WithViscousPerDirection(urdf, options.viscous_per_direction);
  SerialRobotIdentification run;
  SerialRobotFitOptions fit_options = options.fit;
  fit_options.prior_drives = robot.drives;
  std::string window_note;
  if (options.window_from_logs) {
    const double step = SlowestSerialLogStep(logs);
    if (kSerialWindowSteps * step > fit_options.half_window) {
      window_note = fmt::format("differentiator half window {:.3g} s: {:g} steps of the log ({:.3g} s, about {:.3g} Hz), "
                                "as the default {:.3g} s spans fewer than 2 samples each side there (‹window› sets it)",
                                kSerialWindowSteps * step, kSerialWindowSteps, step, 1.0 / step, fit_options.half_window);
      fit_options.half_window = kSerialWindowSteps * step;
    }
  }
  run.result = FitSerialRobot(robot.robot, logs, fit_options);
  SerialRobotFitOutput& r = run.result;
  if (!window_note.empty()) r.fit.notes.push_back(window_note);
  for (const std::string& note : robot.notes) r.fit.notes.push_back(note);
  run.consistent = FitConsistentParameters(robot.robot, r, ConsistentPrior{options.prior_weight, robot.drives});
  UseConsistent(run);
  for (std::size_t j = 0; j < robot.robot.size(); ++j) {
    run.section.bodies.push_back({robot.robot.joints[j].body, run.consistent.bodies[j]});
    SerialDriveEntry drive{robot.robot.joints[j].name, run.consistent.drives[j], {}};
    for (const SerialDriveTerm* term : SerialDriveTerms()) {
      if (!term->always() && term->Asked(robot.robot.joints[j])) drive.asked.emplace_back(term->key());
    }
    run.section.drives.push_back(std::move(drive));
  }
  run.section.urdf = urdf_path;
  run.section.urdf_sha256 = urdf_sha256;
  run.section.half_window = fit_options.half_window;
  for (std::size_t k = 0; k < r.base.base.size(); ++k) {
    SerialBaseEntry e;
    e.lead = r.parameter_names[r.base.base[k]];
    for (const auto& [column, c] : r.base.combination[k]) e.combination.emplace_back(r.parameter_names[column], c);
    e.value = std::isnan(r.held[k]) ? run.consistent.base[k] : r.held[k];
    run.section.base.push_back(std::move(e));
  }
  // Trace and plot: each joint's measured and predicted torque per log, by
  // the consistent base parameters the file holds; the joints' statistics
  // over every log are theirs too, so that the summary describes the file
  // (what `validate` of the same logs reports), not the unconstrained fit.
  const std::vector<double> values = r.BaseValues();
  run.trace_csv = "# joint torques [N m or N]: measured and predicted by the base parameters (docs/models.md#serial-robot)\n"
                  "log,t,joint,tau_measured,tau_model\n";
  std::vector<std::vector<double>> all_measured(r.joints.size()), all_predicted(r.joints.size());
  for (std::size_t l = 0; l < logs.size(); ++l) {
    const SerialPrediction p = PredictSerialRobot(robot.robot, r.base, values, logs[l], fit_options.half_window);
    for (std::size_t j = 0; j < p.joints.size() && j < all_measured.size(); ++j) {
      all_measured[j].insert(all_measured[j].end(), p.measured[j].begin(), p.measured[j].end());
      all_predicted[j].insert(all_predicted[j].end(), p.predicted[j].begin(), p.predicted[j].end());
    }
    for (std::size_t k = 0; k < p.time.size() && options.trace; ++k) {
      for (std::size_t j = 0; j < p.joints.size(); ++j) {
        run.trace_csv += fmt::format("{},{},{},{:.6g},{:.6g}\n", l + 1, p.time[k], p.joints[j].joint,
                                     p.measured[j][k], p.predicted[j][k]);
      }
    }
    if (l > 0) continue;
    for (std::size_t j = 0; j < p.joints.size(); ++j) {
      std::vector<double> residual(p.time.size());
      for (std::size_t k = 0; k < residual.size(); ++k) residual[k] = p.measured[j][k] - p.predicted[j][k];
      run.panels.push_back({fmt::format("{} along {}", p.joints[j].joint, logs[l].path),
                            "torque",
                            {{"measured", p.time, p.measured[j], true}, {"model", p.time, p.predicted[j], false},
                             {"residual", p.time, residual, false, true}}});
    }
  }
  for (std::size_t j = 0; j < r.joints.size(); ++j) {
    const double weight_std = r.joints[j].weight_std;
    r.joints[j] = CalcSerialJointStatistics(r.joints[j].joint, all_measured[j], all_predicted[j]);
    r.joints[j].weight_std = weight_std;
    // The file's and the JSON's channel statistics likewise (one channel per joint).
    if (j < r.fit.channels.size()) {
      r.fit.channels[j].rmse = r.joints[j].rmse;
      r.fit.channels[j].fit_percent = r.joints[j].fit_percent;
      r.fit.channels[j].relative_error_percent = r.joints[j].relative_error_percent;
    }
  }
  for (const auto& j : r.joints) {
    if (j.relative_error_percent > kPoorRelativeErrorPercent) {
      r.fit.warnings.push_back(fmt::format(
          "joint {}: the model leaves {:.0f} % of its torque unexplained (relative error; docs/models.md#serial-robot): "
          "an effect the model lacks (elasticity, a cable, a payload), a wrong URDF, or a torque column in other units",
          j.joint, j.relative_error_percent));
    }
  }
  run.summary = Summary(robot.robot, run);
  return run;
}

}  // namespace driveid
