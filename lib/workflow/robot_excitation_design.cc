#include "workflow/robot_excitation_design.h"

#include <cmath>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"
#include "fit/robot/serial_robot_fit.h"
#include "params/serial_robot_section.h"
#include "models/serial_dynamics.h"

namespace driveid {

bool RobotDesignRequest::IsValid(std::string* error) const {
  bool positive = true;
  for (double v : noise) positive = positive && Positive(v);
  return OptionCheck(error).Require(positive, "‹noise›: every torque noise must be a finite number > 0");
}

namespace {

// The prior's theta: the fit's consistent bodies and drives where it has
// them (matched by name), else the URDF's inertials and zero drives.
Eigen::VectorXd PriorTheta(const SerialRobot& robot, const RobotDesignRequest& r) {
  SerialRobot prior = robot;
  std::vector<SerialDriveParameters> drives(robot.size());
  const SerialRobotSection* s = r.prior ? r.prior->Find<SerialRobotSection>() : nullptr;
  if (r.prior && !s) throw InputError(fmt::format("{}: no 'serial_robot' section (drivetrain-fit robot ‹urdf›)", r.params_path));
  if (s && !s->bodies.empty()) {
    if (s->bodies.size() != robot.size() || s->drives.size() != robot.size()) {
      throw InputError(fmt::format("{}: its bodies and drives are not the URDF's robot's", r.params_path));
    }
    for (std::size_t j = 0; j < robot.size(); ++j) {
      if (s->bodies[j].link != robot.joints[j].body || s->drives[j].joint != robot.joints[j].name) {
        throw InputError(fmt::format("{}: body {} is not the URDF's link {}", r.params_path, s->bodies[j].link,
                                     robot.joints[j].body));
      }
      prior.bodies[j] = s->bodies[j].parameters;
      drives[j] = s->drives[j].drive;
    }
  }
  return SerialParameterVector(prior, drives);
}

// sigma_j: given, else the prior fit's rmse x inflation of the joint's channel.
std::vector<double> JointNoise(const SerialRobot& robot, const RobotDesignRequest& r) {
  const std::size_t n = robot.size();
  if (r.noise.size() == 1) return std::vector<double>(n, r.noise.front());
  if (r.noise.size() == n) return r.noise;
  if (!r.noise.empty()) {
    throw OptionError(fmt::format("‹noise›: {} values for {} joints: give one, or one per joint", r.noise.size(), n));
  }
  std::vector<double> out;
  for (const SerialJoint& joint : robot.joints) {
    double rmse = 0.0, inflation = 1.0;
    if (r.prior) {
      for (const auto& [name, value] : r.prior->fit_rmse) if (name == joint.name) rmse = value;
      for (const auto& [name, value] : r.prior->fit_inflation) if (name == joint.name) inflation = value;
    }
    if (!r.prior) throw OptionError("‹noise›: without a prior fit (‹params›) give the torque noise");
    if (!(rmse > 0.0)) {
      throw OptionError(fmt::format("‹noise›: {} has no residual rmse for joint '{}' to take its torque noise from; "
                                    "give ‹noise›", r.params_path, joint.name));
    }
    out.push_back(rmse * std::max(1.0, inflation));
  }
  return out;
}

std::string Oneline(std::string text) {
  for (char& c : text) if (c == '\n' || c == '\r') c = ' ';
  return text;
}

std::string Limit(double value) { return std::isfinite(value) ? fmt::format("{:.4g}", value) : "-"; }

std::string FormatDesign(const RobotDesign& d, const RobotDesignOptions& o,
                         const std::vector<std::string>& base_names, const std::vector<double>& prior,
                         const std::vector<double>& noise) {
  std::string out = fmt::format(
      "design robot: a Fourier trajectory per joint, {} harmonics of {:.4g} Hz (period {:.4g} s), {:g} s at {:g} Hz, "
      "criterion {} (docs/models.md#serial-robot-excitation)\n",
      o.harmonics, 1.0 / d.period, d.period, o.duration, o.rate, o.criterion == "a" ? "A" : "D");
  out += fmt::format("{:<16} {:>9} {:>9} {:>9} {:>9} {:>8} {:>9} {:>9} {:>8} {:>8}  {}\n", "joint", "start", "lowest",
                     "highest", "|qd| max", "limit", "|qdd| max", "|tau| max", "limit", "noise", "binding");
  for (std::size_t j = 0; j < d.joints.size(); ++j) {
    const RobotDesignJoint& r = d.joints[j];
    out += fmt::format("{:<16} {:>9.4g} {:>9.4g} {:>9.4g} {:>9.4g} {:>8} {:>9.4g} {:>9.4g} {:>8} {:>8.3g}  {}\n", r.name,
                       r.start, r.lowest, r.highest, r.peak_rate, Limit(r.rate_limit), r.peak_acceleration,
                       r.peak_torque, Limit(r.torque_limit), noise[j], r.binding);
  }
  out += fmt::format("condition number of the column-normalised base regressor: {:.4g}\n", d.condition_number);
  out += fmt::format("{:>4} {:>12} {:>12} {:>10}  {}\n", "base", "prior", "pred. std", "std/|prior|", "combination");
  for (std::size_t k = 0; k < base_names.size(); ++k) {
    const double rel = std::abs(prior[k]) > 0.0 ? d.predicted_std[k] / std::abs(prior[k]) : NAN;
    out += fmt::format("{:>4} {:>12.5g} {:>12.4g} {:>10.3g}  {}\n", k + 1, prior[k], d.predicted_std[k], rel, base_names[k]);
  }
  return out;
}

}  // namespace

ExcitationDesignRun DesignRobotRun(const SerialRobot& robot, const RobotDesignOptions& design,
                                   const RobotDesignRequest& r) {
  RequireValid(r);
  for (const SerialJoint& j : robot.joints) {
    if (j.mimic >= 0) {
      throw InputError(fmt::format("joint '{}' mimics '{}': designing a robot's excitation with mimic joints is not "
                                   "supported (their limits would bind through their leaders')",
                                   j.name, robot.joints[static_cast<std::size_t>(j.mimic)].name));
    }
  }
  const Eigen::VectorXd theta = PriorTheta(robot, r);
  const std::vector<double> noise = JointNoise(robot, r);
  const BaseParameters base = SerialBaseParameters(robot);
  const RobotDesign d = DesignRobotExcitation(robot, theta, base.base, noise, design);
  const Eigen::VectorXd beta = base.regroup * theta;
  const std::vector<double> prior(beta.data(), beta.data() + beta.size());
  ExcitationDesignRun out;
  out.printed = FormatDesign(d, design, base.names, prior, noise);
  const SampledRobotTrajectory t = SampleRobotTrajectory(d, design.rate, design.duration);
  if (r.csv) {
    std::string csv = "# serial robot trajectory (docs/formats.md#robot-trajectories) designed by: " +
                      Oneline(r.command_line) + "\n";
    csv += fmt::format("# predicted std of the base parameters (docs/models.md#serial-robot-excitation), condition "
                       "number {:.4g}:", d.condition_number);
    for (double s : d.predicted_std) csv += fmt::format(" {:.4g}", s);
    csv += "\nt";
    for (const SerialJoint& j : robot.joints) csv += fmt::format(",q_{0},qd_{0},qdd_{0}", j.name);
    csv += "\n";
    auto sink = std::back_inserter(csv);
    for (std::size_t k = 0; k < t.time.size(); ++k) {
      fmt::format_to(sink, "{:.9g}", t.time[k]);
      for (std::size_t j = 0; j < robot.size(); ++j) {
        fmt::format_to(sink, ",{:.10g},{:.10g},{:.10g}", t.position[j][k], t.rate[j][k], t.acceleration[j][k]);
      }
      csv += '\n';
    }
    out.csv = std::move(csv);
  }
  if (r.plot) {
    for (std::size_t j = 0; j < robot.size(); ++j) {
      PlotPanel panel;
      panel.title = robot.joints[j].name;
      panel.y_label = robot.joints[j].type == SerialJointType::kPrismatic ? "q [m]" : "q [rad]";
      panel.lines.push_back({"designed", t.time, t.position[j]});
      out.panels.push_back(std::move(panel));
    }
  }
  return out;
}

}  // namespace driveid
