// What the elastic joint's simulators give (sim/joint_simulator.h, the
// exact one of sim/joint_exact_simulator.h): the terms they differentiate
// by and the states, sensitivities and friction modes at the samples.
#pragma once

#include <vector>

namespace driveid {

/// Indices of the simulated terms (JointParameterTable order).
enum JointTerm {
  kJointMotorInertia = 0,
  kJointLinkInertia,
  kJointStiffness,
  kJointDamping,
  kJointMotorViscous,
  kJointMotorCoulomb,
  kJointLinkViscous,
  kJointLinkCoulomb,  // not simulated
  kJointOffset,
  kJointGravityCos,
  kJointGravitySin,
  // The initial state x_i(t_0) (sensitivity s_i(t_0) = e_i): the start of a
  // log is measured, not known, and an output-error fit estimates it.
  kJointInitialMotorAngle,
  kJointInitialMotorRate,
  kJointInitialLinkAngle,
  kJointInitialLinkRate,
};
/// The state index of an initial-state term, or -1 for a parameter.
inline int InitialStateIndex(int term) { return term >= kJointInitialMotorAngle ? term - kJointInitialMotorAngle : -1; }

struct JointStateResponse {
  /// theta_m, omega_m, theta_l, omega_l at t_k, row-major (sample k, state i).
  std::vector<double> state;
  /// d x_i(t_k) / d p_j at (k * P + j) * 4 + i.
  std::vector<double> sensitivity;
  std::vector<int> mode;  ///< motor friction mode at t_k (-1, 0, +1)
  int switch_count = 0;
};

}  // namespace driveid
