// Physically consistent serial-robot parameters (fit/consistent_parameters.h)
// on the independent reference arm: every body physical; where the truth is
// physical the consistent base parameters stay within their std of the
// unconstrained ones; an estimate pushed outside the physical set is pulled
// back and the shift is reported.
#include <catch2/catch.hpp>

#include "fit/consistent_parameters.h"
#include "fit/serial_robot_fit.h"
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
  const ConsistentParameters c = FitConsistentParameters(robot, out.base, out.fit, 1e-4);
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
  const ConsistentParameters c = FitConsistentParameters(robot, out.base, out.fit, 1e-4);
  for (const auto& b : c.bodies) CHECK(PseudoInertiaMargin(b) >= -1e-12);
  CHECK(c.base[k] > 0.0);
  INFO("largest shift " << c.largest_shift << " std (" << c.largest_shift_name << "), Izz_fore -> " << c.base[k]);
  CHECK(c.largest_shift > 2.0);  // the warning's threshold (workflow/serial_robot_identification.cc)
}
