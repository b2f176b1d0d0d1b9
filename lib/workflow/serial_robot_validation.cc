#include "workflow/serial_robot_validation.h"

#include <cmath>

#include <fmt/format.h>

#include "core/errors.h"
#include "fit/core/adequacy.h"
#include "fit/robot/serial_robot_fit.h"
#include "models/serial_dynamics.h"
#include "sim/mujoco_inverse.h"

namespace driveid {
namespace {

// The section's base parameters must be the URDF's own: same lead columns
// and combinations (coefficients as written, 10 digits).
std::vector<double> MatchedValues(const SerialRobotSection& section, const BaseParameters& base,
                                  const std::vector<std::string>& names, const std::string& path) {
  if (section.base.size() != base.base.size()) {
    throw InputError(fmt::format("{}: serial_robot.base has {} base parameters, the URDF's robot {}: the file was "
                                 "written for another robot or URDF",
                                 path, section.base.size(), base.base.size()));
  }
  std::vector<double> values;
  for (std::size_t k = 0; k < base.base.size(); ++k) {
    const SerialBaseEntry& e = section.base[k];
    bool same = e.lead == names[base.base[k]] && e.combination.size() == base.combination[k].size();
    for (std::size_t i = 0; same && i < e.combination.size(); ++i) {
      const auto& [column, c] = base.combination[k][i];
      same = e.combination[i].first == names[column] && std::abs(e.combination[i].second - c) <= 1e-9 * (1.0 + std::abs(c));
    }
    if (!same) {
      throw InputError(fmt::format("{}: serial_robot.base[{}] ({}) is not the URDF's base parameter {} ({}): the file "
                                   "was written for another robot or URDF",
                                   path, k, e.lead, names[base.base[k]], base.names[k]));
    }
    values.push_back(e.value);
  }
  return values;
}

ValidatedLog Validated(const std::string& path, const std::string& joint, const std::vector<double>& time,
                       std::vector<double> measured, std::vector<double> model) {
  ValidatedLog v;
  v.time = time;
  v.measured = std::move(measured);
  v.model = std::move(model);
  std::vector<double> residual(v.time.size());
  for (std::size_t k = 0; k < residual.size(); ++k) residual[k] = v.measured[k] - v.model[k];
  v.stats = DescribeResiduals(fmt::format("{}:tau_{}", path, joint), v.measured.data(), residual.data(),
                              static_cast<int>(residual.size()));
  return v;
}

}  // namespace

ValidationRun RunSerialRobotValidation(const std::vector<SerialRobotLog>& logs, const SerialRobotSection& section,
                                       const SerialRobot& robot, const std::string& path) {
  const BaseParameters base = SerialBaseParameters(robot);
  const std::vector<double> values = MatchedValues(section, base, SerialParameterNames(robot), path);
  ValidationRun run;
  run.method = "serial robot: each joint's torque by inverse dynamics of the base parameters (docs/models.md#serial-robot)";
  run.title = "serial robot validation: joint torques predicted from the parameter file";
  run.unit = "torque [N m or N]";
  for (const SerialRobotLog& log : logs) {
    const SerialPrediction p = PredictSerialRobot(robot, base, values, log, section.half_window);
    for (std::size_t j = 0; j < p.joints.size(); ++j) {
      run.logs.push_back(Validated(log.path, p.joints[j].joint, p.time, p.measured[j], p.predicted[j]));
    }
  }
  RequireValidated(run.logs);
  return run;
}

SerialRobot MjcfJoints(const std::string& mjcf) {
  SerialRobot robot;
  for (const std::string& name : MujocoJointNames(mjcf)) {
    SerialJoint joint;
    joint.name = name;
    robot.joints.push_back(joint);
  }
  robot.bodies.resize(robot.joints.size());
  return robot;
}

double DefaultSerialHalfWindow() { return SerialRobotFitOptions{}.half_window; }

ValidationRun RunMujocoSerialValidation(const std::vector<SerialRobotLog>& logs, const std::string& mjcf,
                                        const SerialRobot& joints, double half_window) {
  std::vector<std::string> names;
  for (const SerialJoint& j : joints.joints) names.push_back(j.name);
  ValidationRun run;
  run.title = "serial robot validation in MuJoCo: joint torques predicted from the MJCF";
  run.unit = "torque [N m or N]";
  for (const SerialRobotLog& log : logs) {
    const SerialMotion m = DifferentiateSerialLog(joints, log, half_window);
    if (m.sample.empty()) {
      throw InputError(fmt::format("{}: shorter than the differentiator's window ({} s each side)", log.path, half_window));
    }
    MujocoInverseResponse r = MujocoInverseDynamics(mjcf, names, m.q, m.qd, m.qdd);
    run.method = fmt::format("serial robot in MuJoCo {}: each joint's control by MuJoCo's inverse dynamics "
                             "(mj_inverse) of the logged motion (docs/export.md#validation-in-mujoco)", r.library);
    for (std::size_t j = 0; j < names.size(); ++j) {
      std::vector<double> measured;
      for (std::size_t k : m.sample) measured.push_back(log.torque[j][k]);
      run.logs.push_back(Validated(log.path, names[j], m.time, std::move(measured), std::move(r.control[j])));
    }
  }
  RequireValidated(run.logs);
  return run;
}

}  // namespace driveid
