// Physically consistent serial-robot parameters (fit/robot/consistent_parameters.h)
// on the independent reference arm: every body physical; where the truth is
// physical the consistent base parameters stay within their std of the
// unconstrained ones; an estimate pushed outside the physical set is pulled
// back and the shift is reported.
#include <catch2/catch.hpp>

#include "core/errors.h"
#include "fit/robot/consistent_parameters.h"
#include "fit/robot/serial_robot_fit.h"
#include "models/pseudo_inertia.h"
#include "models/serial_dynamics.h"
#include "support/reference_serial_arm.h"
#include "support/serial_arm_robot.h"

using namespace driveid;

namespace {

// The "URDF" values the prior pulls towards: 20 % off the truth.
SerialRobot ToRobot(const reference::Arm& arm) { return driveid::testing::ToSerialRobot(arm, nullptr, 1.2, 0.9); }

SerialRobotFitOutput Fit(const SerialRobot& robot, const reference::Arm& arm) {
  reference::ArmLogOptions o;
  o.seed = 4;
  const reference::ArmLog a = reference::SimulateArm(arm, o);
  return FitSerialRobot(robot, {driveid::testing::ToSerialLog(a)}, {});
}

}  // namespace

TEST_CASE("consistent parameters: physical bodies, base parameters within their std") {
  const reference::Arm arm = reference::ThreeJointArm();
  const SerialRobot robot = ToRobot(arm);
  const SerialRobotFitOutput out = Fit(robot, arm);
  const ConsistentParameters c = FitConsistentParameters(robot, out, ConsistentPrior{});
  INFO(c.iterations << " iterations: " << c.termination);
  CHECK(c.converged);
  REQUIRE(c.bodies.size() == 3);
  for (const auto& b : c.bodies) CHECK(PseudoInertiaMargin(b) >= -1e-12);
  for (const auto& d : c.drives) {
    CHECK(d.viscous >= 0.0);
    CHECK(d.coulomb >= 0.0);
  }
  INFO("largest shift " << c.largest_shift << " std (" << c.largest_shift_name << "), chi2 " << c.chi2);
  CHECK(c.largest_shift < 1.0);
}

TEST_CASE("consistent parameters: an unphysical estimate is pulled back and the shift reported") {
  const reference::Arm arm = reference::ThreeJointArm();
  const SerialRobot robot = ToRobot(arm);
  SerialRobotFitOutput out = Fit(robot, arm);
  // The Izz-led combination of the last body (its inertia about the elbow
  // axis, armature included) made negative: no body has that.
  const std::vector<std::string> names = SerialParameterNames(robot);
  std::size_t k = out.base.base.size();
  for (std::size_t i = 0; i < out.base.base.size(); ++i) {
    if (names[out.base.base[i]] == "Izz_fore") k = i;
  }
  REQUIRE(k < out.base.base.size());
  out.fit.estimates[k].value = -0.5;  // an inertia about the elbow axis below zero
  const ConsistentParameters c = FitConsistentParameters(robot, out, ConsistentPrior{});
  for (const auto& b : c.bodies) CHECK(PseudoInertiaMargin(b) >= -1e-12);
  CHECK(c.base[k] > 0.0);
  INFO("largest shift " << c.largest_shift << " std (" << c.largest_shift_name << "), Izz_fore -> " << c.base[k]);
  CHECK(c.largest_shift > 2.0);  // the warning's threshold (workflow/serial_robot_identification.cc)
}

namespace {

// Joints yaw and shoulder on sums of sines; the elbow held at 0.3 rad by its
// drive (a joint the experiment left out).
reference::ArmLogOptions ElbowAtRest() {
  reference::ArmLogOptions o;
  o.seed = 11;
  o.trajectory = [](double t, Eigen::VectorXd& q, Eigen::VectorXd& qd, Eigen::VectorXd& qdd) {
    q = Eigen::VectorXd::Zero(3);
    qd = q;
    qdd = q;
    const double f[2][2] = {{0.1, 0.37}, {0.13, 0.29}}, a[2][2] = {{0.8, 0.3}, {0.6, 0.25}};
    for (int j = 0; j < 2; ++j) {
      for (int h = 0; h < 2; ++h) {
        const double w = 2.0 * M_PI * f[j][h];
        q(j) += a[j][h] * std::sin(w * t);
        qd(j) += a[j][h] * w * std::cos(w * t);
        qdd(j) -= a[j][h] * w * w * std::sin(w * t);
      }
    }
    q(2) = 0.3;
  };
  return o;
}

}  // namespace

TEST_CASE("held base parameters: an unexcited joint is refused with what to do; held at the prior it fits") {
  const reference::Arm arm = reference::ThreeJointArm();
  std::vector<SerialDriveParameters> drives;
  const SerialRobot robot = driveid::testing::ToSerialRobot(arm, &drives);
  const SerialRobotLog log = driveid::testing::ToSerialLog(reference::SimulateArm(arm, ElbowAtRest()));
  std::string refusal;
  try {
    FitSerialRobot(robot, {log}, {});
  } catch (const IdentificationError& e) {
    refusal = e.what();
  }
  INFO(refusal);
  REQUIRE(refusal.find("‹free›") != std::string::npos);
  // Every base parameter but those of the resting elbow's drive:
  // held at the prior (here the truth), the rest estimated.
  SerialRobotFitOptions options;
  options.prior_drives = drives;
  const BaseParameters base = SerialBaseParameters(robot);
  const std::vector<std::string> names = SerialParameterNames(robot);
  for (std::size_t k = 0; k < base.base.size(); ++k) {
    const std::string& lead = names[base.base[k]];
    if (lead.find("elbow") == std::string::npos) options.free.push_back(lead);
  }
  const SerialRobotFitOutput out = FitSerialRobot(robot, {log}, options);
  REQUIRE(out.fit.estimates.size() == options.free.size());
  CHECK(out.free.size() < out.base.base.size());
  const Eigen::VectorXd truth = out.base.regroup * SerialParameterVector(robot, drives);
  int inside = 0;
  for (std::size_t c = 0; c < out.free.size(); ++c) {
    const ParameterEstimate& e = out.fit.estimates[c];
    const double t = truth(static_cast<Eigen::Index>(out.free[c])), z = (e.value - t) / e.standard_error;
    INFO(e.name << " " << e.value << " +- " << e.standard_error << " truth " << t);
    CHECK(std::abs(z) < 4.0);
    inside += e.ci95_low <= t && t <= e.ci95_high;
  }
  CHECK(inside >= static_cast<int>(out.free.size()) - 2);
  // The consistent fit keeps the held ones at their values.
  const ConsistentParameters c = FitConsistentParameters(robot, out, ConsistentPrior{1e-4, drives});
  const std::vector<double> values = out.BaseValues();
  for (std::size_t k = 0; k < out.held.size(); ++k) {
    if (std::isnan(out.held[k])) continue;
    INFO(out.base.names[k]);
    CHECK(c.base[k] == Approx(out.held[k]).epsilon(1e-3).margin(1e-6));
    CHECK(values[k] == out.held[k]);
  }
}

TEST_CASE("held base parameters: a name that is no base parameter is refused by name") {
  const reference::Arm arm = reference::ThreeJointArm();
  const SerialRobot robot = ToRobot(arm);
  const SerialRobotLog log = driveid::testing::ToSerialLog(reference::SimulateArm(arm, {}));
  SerialRobotFitOptions options;
  options.free = {"no_such"};
  CHECK_THROWS_WITH(FitSerialRobot(robot, {log}, options), Catch::Contains("'no_such'"));
  // A parameter folded into another base parameter names that one.
  const BaseParameters base = SerialBaseParameters(robot);
  const std::vector<std::string> names = SerialParameterNames(robot);
  std::string folded;
  for (const auto& combination : base.combination) {
    if (combination.size() > 1) folded = names[combination[1].first];
  }
  REQUIRE_FALSE(folded.empty());
  options.free = {folded};
  CHECK_THROWS_AS(FitSerialRobot(robot, {log}, options), OptionError);
}

// The prior is a tie-breaker (docs/models.md#physical-consistency): at its
// default weight, 1e-4 of one std of the data (kConsistentPriorWeight), a
// body the data determine keeps the data's base parameters — a pendulum
// whose "URDF" is twice too heavy, its centre half as far, moves them by
// under 1e-4 of their std (the pull grows with the weight: 3e-6 std here at
// the default, 3e-4 at a hundred times it), while the parameters the data
// cannot see (its mass, its inertia about the other axes) come from the
// prior, physical.
TEST_CASE("consistent parameters: at the default prior weight the data decide what they determine") {
  reference::Arm arm;
  arm.gravity = Eigen::Vector3d(0.0, -9.81, 0.0);
  reference::ArmJoint pivot;
  pivot.name = "pivot";
  pivot.body = "rod";
  pivot.mass = 2.0;
  pivot.centre = Eigen::Vector3d(0.3, 0.05, 0.0);
  pivot.inertia_at_centre = Eigen::Vector3d(0.001, 0.02, 0.02).asDiagonal();
  pivot.armature = 0.01;
  pivot.viscous = 0.2;
  pivot.coulomb = 0.5;
  arm.joints.push_back(pivot);
  const SerialRobot urdf = driveid::testing::ToSerialRobot(arm, nullptr, 2.0, 0.5);
  reference::ArmLogOptions o;
  o.seed = 5;
  o.duration = 10.0;
  const SerialRobotFitOutput out =
      FitSerialRobot(urdf, {driveid::testing::ToSerialLog(reference::SimulateArm(arm, o))}, {});
  const ConsistentParameters c = FitConsistentParameters(urdf, out, ConsistentPrior{});
  INFO("largest shift " << c.largest_shift << " std (" << c.largest_shift_name << "), chi2 " << c.chi2);
  CHECK(c.converged);
  CHECK(c.largest_shift < 1e-4);
  REQUIRE(c.bodies.size() == 1);
  CHECK(PseudoInertiaMargin(c.bodies[0]) >= -1e-12);
  CHECK(c.bodies[0][0] == Approx(urdf.bodies[0][0]).epsilon(1e-3));  // the mass: unseen, the prior's
}
