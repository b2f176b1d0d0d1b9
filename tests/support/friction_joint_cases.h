// The closed-loop friction joint of tests/support/reference_joint_friction.h
// as the fits take it: its log as a JointLog, and a start far from the
// truth (as a user's first guess), shared by the output-error recovery and
// coverage tests.
#pragma once

#include <string>

#include "logs/joint_log.h"
#include "models/joint.h"
#include "support/reference_joint_friction.h"

namespace driveid::testing {

inline JointLog ToJointLog(const FrictionJointLog& g, const std::string& path) {
  JointLog log;
  log.path = path;
  log.time = g.t;
  log.motor_position = g.q_motor;
  log.link_position = g.q_link;
  log.torque = g.tau;
  return log;
}

/// Start values 20-50 % off (fixed: link Coulomb 0).
inline JointSection FarJointStart(const FrictionJointTruth& t) {
  JointSection s;
  s.gear_ratio = t.gear_ratio;
  s.motor_inertia = 1.2 * t.motor_inertia;
  s.link_inertia = 2.0 / 3.0 * t.link_inertia;
  s.stiffness = 1.5 * t.stiffness;
  s.damping = s.motor_viscous = s.motor_coulomb = 1.0;
  s.link_viscous = s.link_coulomb = s.offset = 0.0;
  return s;
}

}  // namespace driveid::testing
