// Simulation of the elastic two-mass joint of models/joint.h from a held
// (zero-order-hold) motor torque, with motor Coulomb friction that truly
// sticks, and forward sensitivities of the four states to chosen joint
// terms (docs/models.md#joint-output-error). Link side, states
// x = (theta_m, omega_m, theta_l, omega_l), input u = n tau:
//   J_m omega_m' = u - k D - d D' - b_m omega_m - c_m m - tau_0
//   J_l omega_l' = k D + d D' - b_l omega_l - g_c cos theta_l - g_s sin theta_l
// with D = theta_m - theta_l and m the motor's friction mode. The link's
// Coulomb friction is not simulated (callers refuse it). Modes as in the
// drive train (sim/drivetrain_simulator.h): sliding m = +-1 with root
// g = omega_m; at omega_m = 0 the motor sticks if the static torque
//   N = u - k D + d omega_l - tau_0
// lies within [-c_m, c_m], else it slides towards N. Stuck, theta_m and
// omega_m = 0 hold while the link swings on the spring; roots N -+ c_m
// break it away (the field is continuous there: nothing jumps). Sliding into
// omega_m = 0 at t*(p): s+ = s- + (f- - f+) dt*/dp, dt*/dp = -s_omega_m- / omega_m'-,
// which gives s_omega_m+ = 0 when it sticks. u[k] is held on [t_k, t_{k+1});
// samples are taken at t_k before the new torque applies.
// Without gravity terms the joint is linear within a mode and each sample
// interval is solved exactly by matrix exponentials
// (sim/joint_exact_simulator.cc); with them, CVODES integrates (restarted
// at every change of the torque).
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "models/joint.h"
#include "sim/joint_exact_simulator.h"
#include "sim/joint_response.h"

namespace driveid {

class JointSimulator {
 public:
  /// `terms`: JointTerm indices whose sensitivities Simulate computes.
  /// Absolute tolerances of the angles and of the rates [rad, rad/s].
  JointSimulator(std::vector<int> terms, double angle_tolerance, double rate_tolerance);
  ~JointSimulator();
  JointSimulator(const JointSimulator&) = delete;
  JointSimulator& operator=(const JointSimulator&) = delete;

  /// Simulates from x0 at time[0] under u = motor_torque (link side, n tau).
  /// Needs J_m, J_l > 0. Throws IdentificationError when the integrator
  /// fails or chatters.
  void Simulate(const JointParameters& p, const std::vector<double>& time, const std::vector<double>& motor_torque,
                const std::array<double, 4>& x0, bool with_sensitivities, JointStateResponse* response);

  /// Integrate with CVODES even where the exact path applies (for tests).
  void set_use_integrator(bool use) { use_integrator_ = use; }

 private:
  class System;
  std::unique_ptr<System> system_;
  std::unique_ptr<JointExactSimulator> exact_;
  std::vector<int> terms_;
  bool use_integrator_ = false;
};

}  // namespace driveid
