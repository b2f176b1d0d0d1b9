// The serial robot's identification (fit/robot/serial_robot_fit.h) on logs of an
// independent three-joint arm (tests/support/reference_serial_arm.h): the
// base parameters' 95 % intervals hold the truth at their promised rate
// over noise seeds (coloured torque noise, quantised encoders, jittered
// stamps rounded to 1 ms; 0.98 measured, with the processing and timing
// term), missing neither side more than by chance, and
// each joint's friction is recovered; and in closed loop (a drive's PD with
// a model feed-forward, stick-slip at reversals, an unlogged disturbance).
#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include "fit/robot/serial_robot_fit.h"
#include "models/serial_dynamics.h"
#include "support/reference_serial_arm.h"
#include "support/serial_arm_robot.h"

using namespace driveid;

using driveid::testing::ToSerialLog;
using driveid::testing::ToSerialRobot;

namespace {

// The fit's estimate named `name` (the test fails without one).
ParameterEstimate EstimateNamed(const SerialRobotFitOutput& out, const std::string& name) {
  for (const auto& e : out.fit.estimates) {
    if (e.name == name) return e;
  }
  FAIL("no estimate " << name);
  return ParameterEstimate{};
}

}  // namespace

TEST_CASE("serial robot: base-parameter intervals hold the truth over seeds, from both sides") {
  const reference::Arm arm = reference::ThreeJointArm();
  std::vector<SerialDriveParameters> drives;
  const SerialRobot robot = ToSerialRobot(arm, &drives);
  const Eigen::VectorXd theta = SerialParameterVector(robot, drives);
  int inside = 0, below = 0, above = 0, total = 0;
  const int seeds = 40;
  for (int seed = 1; seed <= seeds; ++seed) {
    reference::ArmLogOptions o;
    o.seed = static_cast<unsigned>(seed);
    const SerialRobotFitOutput out = FitSerialRobot(robot, {ToSerialLog(reference::SimulateArm(arm, o))}, {});
    const Eigen::VectorXd truth = out.base.regroup * theta;
    for (std::size_t k = 0; k < out.fit.estimates.size(); ++k) {
      const ParameterEstimate& e = out.fit.estimates[k];
      const double t = truth(static_cast<Eigen::Index>(k));
      ++total;
      if (t < e.ci95_low) {
        ++below;
      } else if (t > e.ci95_high) {
        ++above;
      } else {
        ++inside;
      }
    }
  }
  const double coverage = static_cast<double>(inside) / total;
  INFO("coverage " << coverage << " over " << total << " intervals; truth below " << below << ", above " << above);
  CHECK(coverage >= 0.88);
  CHECK(coverage <= 0.99);
  CHECK(below <= 0.07 * total);
  CHECK(above <= 0.07 * total);
}

TEST_CASE("serial robot: friction and offsets per joint recovered inside their intervals") {
  const reference::Arm arm = reference::ThreeJointArm();
  std::vector<SerialDriveParameters> drives;
  const SerialRobot robot = ToSerialRobot(arm, &drives);
  reference::ArmLogOptions o;
  o.seed = 7;
  o.duration = 40.0;
  const SerialRobotFitOutput out = FitSerialRobot(robot, {ToSerialLog(reference::SimulateArm(arm, o))}, {});
  const auto estimate = [&](const std::string& name) { return EstimateNamed(out, name); };
  for (std::size_t j = 0; j < robot.size(); ++j) {
    const std::string& joint = robot.joints[j].name;
    for (const auto& [key, truth] : {std::pair<std::string, double>{"viscous_" + joint, drives[j].viscous},
                                     {"coulomb_" + joint, drives[j].coulomb}}) {
      const ParameterEstimate e = estimate(key);
      INFO(key << " = " << e.value << " +- " << e.standard_error << ", truth " << truth);
      CHECK(std::abs(e.value - truth) <= 0.1 * truth);
      CHECK(std::abs(e.value - truth) <= 3.0 * e.standard_error);
    }
  }
  CHECK(out.joints.size() == 3);
  for (const auto& j : out.joints) CHECK(j.relative_error_percent < 20.0);
}

TEST_CASE("serial robot: viscous friction per direction where asked, recovered inside its interval") {
  // The shoulder's drive: 5 N m s/rad forwards, 3 backwards.
  reference::Arm arm = reference::ThreeJointArm();
  arm.joints[1].viscous = 5.0;
  arm.joints[1].viscous_backwards = 3.0;
  SerialRobot robot = ToSerialRobot(arm);
  robot.joints[1].viscous_per_direction = true;
  reference::ArmLogOptions o;
  o.seed = 12;
  o.duration = 40.0;
  const SerialRobotFitOutput out = FitSerialRobot(robot, {ToSerialLog(reference::SimulateArm(arm, o))}, {});
  const auto estimate = [&](const std::string& name) { return EstimateNamed(out, name); };
  // b = (b+ + b-) / 2 = 4, d = (b+ - b-) / 2 = 1.
  for (const auto& [key, truth] : {std::pair<std::string, double>{"viscous_shoulder", 4.0}, {"viscous_asymmetry_shoulder", 1.0}}) {
    const ParameterEstimate e = estimate(key);
    INFO(key << " = " << e.value << " +- " << e.standard_error << ", truth " << truth);
    CHECK(std::abs(e.value - truth) <= 4.0 * e.standard_error);
    CHECK(e.standard_error < 0.2 * truth);
  }
  // Only where asked: the other joints have no asymmetry.
  for (const auto& e : out.fit.estimates) CHECK(e.name.find("viscous_asymmetry_yaw") == std::string::npos);
}

TEST_CASE("serial robot: a mimic joint (a parallelogram elbow) is fitted from its leader's torque") {
  // The elbow follows the shoulder, q_elbow = 0.5 - q_shoulder (a linkage):
  // two coordinates. The arm's torques come from its independent
  // Lagrangian for all three joints; the linkage carries the elbow's to
  // the shoulder by virtual work, tau_shoulder - tau_elbow, and the log
  // holds the coordinates alone.
  const reference::Arm arm = reference::ThreeJointArm();
  std::vector<SerialDriveParameters> drives;
  SerialRobot robot = ToSerialRobot(arm, &drives);
  robot.joints[2].mimic = 1;
  robot.joints[2].mimic_multiplier = -1.0;
  robot.joints[2].mimic_offset = 0.5;
  const Eigen::VectorXd theta = SerialParameterVector(robot, drives);
  int inside = 0, total = 0;
  double worst = 0.0;
  for (unsigned seed = 1; seed <= 6; ++seed) {
    reference::ArmLogOptions o;
    o.seed = seed;
    o.duration = 30.0;
    o.trajectory = [](double t, Eigen::VectorXd& q, Eigen::VectorXd& qd, Eigen::VectorXd& qdd) {
      q = Eigen::VectorXd::Zero(3);
      qd = q;
      qdd = q;
      const double f[2][3] = {{0.1, 0.23, 0.37}, {0.13, 0.29, 0.41}}, a[2][3] = {{0.8, 0.3, 0.15}, {0.5, 0.25, 0.1}};
      for (int j = 0; j < 2; ++j) {
        for (int h = 0; h < 3; ++h) {
          const double w = 2.0 * M_PI * f[j][h];
          q(j) += a[j][h] * std::sin(w * t);
          qd(j) += a[j][h] * w * std::cos(w * t);
          qdd(j) -= a[j][h] * w * w * std::sin(w * t);
        }
      }
      q(2) = 0.5 - q(1);
      qd(2) = -qd(1);
      qdd(2) = -qdd(1);
    };
    const reference::ArmLog a = reference::SimulateArm(arm, o);
    SerialRobotLog log{"mimic.csv", a.t, {a.q[0], a.q[1]}, {{}, {}}, {a.tau[0], a.tau[1]}};
    for (std::size_t k = 0; k < log.time.size(); ++k) log.torque[1][k] -= a.tau[2][k];
    const SerialRobotFitOutput out = FitSerialRobot(robot, {log}, {});
    REQUIRE(out.joints.size() == 2);
    const Eigen::VectorXd truth = out.base.regroup * theta;
    for (std::size_t c = 0; c < out.free.size(); ++c) {
      const ParameterEstimate& e = out.fit.estimates[c];
      const double t = truth(static_cast<Eigen::Index>(out.free[c]));
      worst = std::max(worst, std::abs(e.value - t) / e.standard_error);
      inside += e.ci95_low <= t && t <= e.ci95_high;
      ++total;
    }
  }
  INFO(inside << " of " << total << " intervals hold the truth; worst " << worst << " std");
  CHECK(inside >= 0.85 * total);
  CHECK(worst < 4.5);
}

TEST_CASE("serial robot: in closed loop (a drive's PD and model feed-forward, an unlogged disturbance) the intervals hold") {
  // The logged torque is the controller's command, the motion the arm's
  // response to it and to a disturbance the log does not see
  // (tests/support/reference_serial_arm.h SimulateArmClosedLoop).
  const reference::Arm arm = reference::ThreeJointArm();
  std::vector<SerialDriveParameters> drives;
  const SerialRobot robot = ToSerialRobot(arm, &drives);
  const Eigen::VectorXd theta = SerialParameterVector(robot, drives);
  int inside = 0, total = 0;
  double worst_tracking = 0.0;
  const int seeds = 8;
  for (int seed = 1; seed <= seeds; ++seed) {
    reference::ArmLogOptions o;
    o.seed = static_cast<unsigned>(seed);
    const reference::ArmLog closed = reference::SimulateArmClosedLoop(arm, o, {});
    const reference::ArmLog open = reference::SimulateArm(arm, o);
    for (std::size_t j = 0; j < 3; ++j) {
      for (std::size_t k = 0; k < closed.q[j].size() && k < open.q[j].size(); ++k) {
        worst_tracking = std::max(worst_tracking, std::abs(closed.q[j][k] - open.q[j][k]));
      }
    }
    const SerialRobotFitOutput out = FitSerialRobot(robot, {ToSerialLog(closed)}, {});
    const Eigen::VectorXd truth = out.base.regroup * theta;
    for (std::size_t k = 0; k < out.fit.estimates.size(); ++k) {
      const ParameterEstimate& e = out.fit.estimates[k];
      const double t = truth(static_cast<Eigen::Index>(k));
      ++total;
      if (t >= e.ci95_low && t <= e.ci95_high) ++inside;
    }
  }
  // The loop follows the reference but not exactly: the fit sees the motion the arm made.
  INFO("largest tracking error " << worst_tracking << " rad");
  CHECK(worst_tracking > 1e-3);
  const double coverage = static_cast<double>(inside) / total;
  INFO("coverage " << coverage << " over " << total << " intervals");
  CHECK(coverage >= 0.88);
  CHECK(coverage <= 0.995);
}

TEST_CASE("serial robot: a coupled wrist (one motor turns two joints) — regressor and the coupled motor's friction") {
  // Six joints; motor 6 turns at q6 - 0.6 q5 (a wrist's differential):
  // its friction acts on that rate and reaches both joints.
  reference::Arm arm = reference::SixJointArm();
  arm.coupling = Eigen::MatrixXd::Identity(6, 6);
  arm.coupling(5, 4) = -0.6;
  std::vector<SerialDriveParameters> drives;
  const SerialRobot robot = ToSerialRobot(arm, &drives);
  const Eigen::VectorXd theta = SerialParameterVector(robot, drives);
  Eigen::MatrixXd y(6, 6 * kSerialColumnsPerJoint);
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd q(6), qd(6), qdd(6);
    for (int j = 0; j < 6; ++j) {
      q(j) = normal(rng);
      qd(j) = normal(rng);
      qdd(j) = normal(rng);
    }
    CalcSerialRegressor(robot, q, qd, qdd, y);
    const Eigen::VectorXd want = reference::ArmTorque(arm, q, qd, qdd);
    CHECK((y * theta - want).cwiseAbs().maxCoeff() < 1e-5 * (1.0 + want.cwiseAbs().maxCoeff()));
  }
  reference::ArmLogOptions o;
  o.seed = 5;
  const SerialRobotFitOutput out = FitSerialRobot(robot, {ToSerialLog(reference::SimulateArm(arm, o))}, {});
  const Eigen::VectorXd truth = out.base.regroup * theta;
  int checked = 0;
  for (std::size_t k = 0; k < out.fit.estimates.size(); ++k) {
    const ParameterEstimate& e = out.fit.estimates[k];
    if (e.name.rfind("viscous_", 0) != 0 && e.name.rfind("coulomb_", 0) != 0) continue;
    INFO(e.name << " = " << e.value << " +- " << e.standard_error << ", truth " << truth(static_cast<Eigen::Index>(k)));
    CHECK(std::abs(e.value - truth(static_cast<Eigen::Index>(k))) < 4.0 * e.standard_error);
    ++checked;
  }
  CHECK(checked == 12);
}
