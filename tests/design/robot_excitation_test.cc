// The serial robot's excitation design (design/robot_excitation.h): the
// trajectory keeps every joint inside its limits on the logging grid and
// starts and ends at rest; refusals name the joint; and the std it
// predicts for the base parameters is the std they achieve — fits of logs
// of the designed trajectory, written by the independent arm simulator
// (tests/support/reference_serial_arm.h: coloured torque noise, quantised
// encoders, jittered stamps), scatter as predicted, from the noise a first
// fit on another trajectory measured.
#include <cmath>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "design/robot_excitation.h"
#include "fit/robot/serial_robot_fit.h"
#include "models/serial_dynamics.h"
#include "support/reference_serial_arm.h"
#include "support/serial_arm_robot.h"

using namespace driveid;

namespace {

SerialRobot LimitedArm(const reference::Arm& arm, std::vector<SerialDriveParameters>* drives) {
  SerialRobot robot = testing::ToSerialRobot(arm, drives);
  for (SerialJoint& j : robot.joints) {
    j.lower = -2.0;
    j.upper = 2.5;
    j.velocity_limit = 2.0;
    j.effort_limit = 120.0;
  }
  return robot;
}

}  // namespace

TEST_CASE("design robot: limits hold on the logging grid, the trajectory starts and ends at rest") {
  const reference::Arm arm = reference::ThreeJointArm();
  std::vector<SerialDriveParameters> drives;
  const SerialRobot robot = LimitedArm(arm, &drives);
  const Eigen::VectorXd theta = SerialParameterVector(robot, drives);
  RobotDesignOptions o;
  o.duration = 20.0;
  o.rate = 200.0;
  o.max_acceleration = 6.0;
  o.evaluations = 600;
  const RobotDesign d = DesignRobotExcitation(robot, theta, SerialBaseParameters(robot).base, {0.5, 0.5, 0.5}, o);
  const SampledRobotTrajectory t = SampleRobotTrajectory(d, o.rate, o.duration);
  const Eigen::Index n = 3;
  double worst_torque = 0.0;
  for (std::size_t k = 0; k < t.time.size(); ++k) {
    Eigen::VectorXd q(n), qd(n), qdd(n);
    for (std::size_t j = 0; j < 3; ++j) {
      const auto i = static_cast<Eigen::Index>(j);
      q(i) = t.position[j][k];
      qd(i) = t.rate[j][k];
      qdd(i) = t.acceleration[j][k];
      REQUIRE(q(i) >= -2.0);
      REQUIRE(q(i) <= 2.5);
      REQUIRE(std::abs(qd(i)) <= 2.0);
      REQUIRE(std::abs(qdd(i)) <= 6.0);
    }
    // The torque from the independent Lagrangian, not the design's own model.
    worst_torque = std::max(worst_torque, reference::ArmTorque(arm, q, qd, qdd).cwiseAbs().maxCoeff());
  }
  CHECK(worst_torque <= 120.0);
  for (std::size_t k : {std::size_t{0}, t.time.size() - 1}) {
    for (std::size_t j = 0; j < 3; ++j) {
      CHECK(t.position[j][k] == Approx(d.joints[j].start).margin(1e-9));
      CHECK(t.rate[j][k] == Approx(0.0).margin(1e-9));
      CHECK(t.acceleration[j][k] == Approx(0.0).margin(1e-9));
    }
  }
  CHECK(d.condition_number > 1.0);
  CHECK(std::isfinite(d.condition_number));
}

TEST_CASE("design robot: refusals name the joint and the option") {
  const reference::Arm arm = reference::ThreeJointArm();
  std::vector<SerialDriveParameters> drives;
  SerialRobot robot = LimitedArm(arm, &drives);
  const Eigen::VectorXd theta = SerialParameterVector(robot, drives);
  const std::vector<std::size_t> base = SerialBaseParameters(robot).base;
  RobotDesignOptions o;
  o.duration = 10.0;
  o.evaluations = 50;
  SerialRobot continuous = robot;
  continuous.joints[1].lower = -std::numeric_limits<double>::infinity();
  continuous.joints[1].upper = std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH(DesignRobotExcitation(continuous, theta, base, {1, 1, 1}, o),
                    Catch::Contains("joint 'shoulder' has no position limits") && Catch::Contains("‹max_position›"));
  SerialRobot weak = robot;
  weak.joints[1].effort_limit = 1.0;  // the shoulder cannot hold the arm up
  CHECK_THROWS_WITH(DesignRobotExcitation(weak, theta, base, {1, 1, 1}, o),
                    Catch::Contains("joint 'shoulder': the prior's torque at rest"));
  o.duration = 0.0;
  CHECK_THROWS_AS(DesignRobotExcitation(robot, theta, base, {1, 1, 1}, o), OptionError);
}

TEST_CASE("design robot: predicted std = achieved std of the base parameters on the designed trajectory") {
  const reference::Arm arm = reference::ThreeJointArm();
  std::vector<SerialDriveParameters> drives;
  const SerialRobot robot = LimitedArm(arm, &drives);
  const Eigen::VectorXd theta = SerialParameterVector(robot, drives);
  // The noise as a first fit on another trajectory meets it: rmse x inflation per joint.
  reference::ArmLogOptions first;
  first.seed = 100;
  const SerialRobotFitOutput prior = FitSerialRobot(robot, {testing::ToSerialLog(reference::SimulateArm(arm, first))}, {});
  std::vector<double> noise;
  for (const ChannelStatistics& c : prior.fit.channels) noise.push_back(c.rmse * c.inflation);
  RobotDesignOptions o;
  o.duration = 20.0;
  o.rate = 200.0;
  o.evaluations = 1500;
  const BaseParameters base = SerialBaseParameters(robot);
  const RobotDesign d = DesignRobotExcitation(robot, theta, base.base, noise, o);
  reference::ArmLogOptions log;
  log.duration = o.duration;
  log.rate = o.rate;
  log.trajectory = [&](double t, Eigen::VectorXd& q, Eigen::VectorXd& qd, Eigen::VectorXd& qdd) {
    for (std::size_t j = 0; j < d.joints.size(); ++j) {
      const ReferenceSample3 s = d.joints[j].reference.At(t);
      const auto i = static_cast<Eigen::Index>(j);
      q(i) = d.joints[j].start + s.position;
      qd(i) = s.rate;
      qdd(i) = s.acceleration;
    }
  };
  const int seeds = 30;
  const std::size_t r = base.base.size();
  std::vector<double> sum(r, 0.0), sum2(r, 0.0);
  for (int seed = 1; seed <= seeds; ++seed) {
    log.seed = static_cast<unsigned>(seed);
    const SerialRobotFitOutput out = FitSerialRobot(robot, {testing::ToSerialLog(reference::SimulateArm(arm, log))}, {});
    for (std::size_t k = 0; k < r; ++k) {
      sum[k] += out.fit.estimates[k].value;
      sum2[k] += out.fit.estimates[k].value * out.fit.estimates[k].value;
    }
  }
  double log_ratio = 0.0, worst = 1.0;
  for (std::size_t k = 0; k < r; ++k) {
    const double mean = sum[k] / seeds;
    const double achieved = std::sqrt(std::max(0.0, (sum2[k] - seeds * mean * mean) / (seeds - 1)));
    const double ratio = achieved / d.predicted_std[k];
    UNSCOPED_INFO(base.names[k] << ": predicted " << d.predicted_std[k] << ", achieved " << achieved << " (x" << ratio << ")");
    log_ratio += std::log(ratio) / static_cast<double>(r);
    worst = std::max(worst, std::max(ratio, 1.0 / ratio));
  }
  INFO("geometric-mean ratio achieved / predicted " << std::exp(log_ratio) << ", worst " << worst);
  CHECK(std::exp(std::abs(log_ratio)) <= 1.5);
  CHECK(worst <= 2.0);
}
