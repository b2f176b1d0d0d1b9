// The reference arm (tests/support/reference_serial_arm.h) as the library's
// SerialRobot and drives, for tests that fit its logs. `scale` multiplies
// its masses and inertias and `centre_scale` its centres (the "URDF" a
// prior pulls towards may be off the truth); 1 gives the truth.
#pragma once

#include <vector>

#include "logs/serial_robot_log.h"
#include "models/serial_robot.h"
#include "support/reference_serial_arm.h"

namespace driveid::testing {

inline SerialRobot ToSerialRobot(const reference::Arm& arm, std::vector<SerialDriveParameters>* drives = nullptr,
                                 double scale = 1.0, double centre_scale = 1.0) {
  SerialRobot robot;
  robot.gravity = arm.gravity;
  for (const auto& j : arm.joints) {
    SerialJoint joint;
    joint.name = j.name;
    joint.body = j.body;
    joint.parent = j.parent;
    joint.origin.rotation = j.rotation;
    joint.origin.translation = j.translation;
    joint.axis = j.axis;
    robot.joints.push_back(joint);
    robot.bodies.push_back(InertialFromCentre(scale * j.mass, centre_scale * j.centre, scale * j.inertia_at_centre));
    if (drives != nullptr) drives->push_back({j.armature, j.viscous, j.coulomb, j.offset});
  }
  robot.coupling = arm.coupling;
  return robot;
}

inline SerialRobotLog ToSerialLog(const reference::ArmLog& a) {
  return {"arm.csv", a.t, a.q, std::vector<std::vector<double>>(a.q.size()), a.tau};
}

}  // namespace driveid::testing
