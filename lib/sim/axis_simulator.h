// Simulation of the rigid axis of models/axis.h from a held (zero-order-
// hold) torque, with Coulomb friction that truly sticks, and forward
// sensitivities of position and rate to chosen axis terms
// (docs/models.md#axis-output-error). States x = (q, v):
//   q' = v,  J v' = u(t) - F(q, v, m),
//   F = sum_{j != J} p_j phi_j(q, v, m) + the nonlinear terms' forces   (models/axis.h; m the mode)
// Modes as in the drive train (sim/drivetrain_simulator.h): sliding m = +-1
// with root g = v; at v = 0 the axis sticks if the static torque
//   N = u - F(q, 0, 0)   (offset, gravity)
// lies within [-(F(q, 0, 0) - F(q, 0, -1)), F(q, 0, +1) - F(q, 0, 0)] (Coulomb,
// per direction, and any breakaway excess), else it slides towards N.
// Stuck, x is constant (no dynamics), and N changes only when u does, at the
// sample times. Sensitivity jumps at a state event t*(p):
//   s+ = s- + (f- - f+) dt*/dp, dt*/dp = -s_v- / v'-,
// so sticking gives s_v+ = 0 (s_q unchanged, v = 0 there) and a reversal
// s_v+ = s_v- v'+ / v'-. u[k] is held on [t_k, t_{k+1}); samples are taken
// at t_k before the new torque applies.
// While every term present is affine in v within a mode and independent of
// q (models/axis_term.h: not gravity, not a breakaway excess) each mode is linear, J v' = u - b_m v
// - c_m, and the simulator solves each held sample in closed form
// (v = v0 e^{-a t} + w (1 - e^{-a t}) / a, a = b_m / J, w = (u - c_m) / J;
// zero crossings and sensitivities likewise): no integrator restart per
// sample, which makes logs whose torque changes every sample (closed loop)
// as cheap as stepped ones. Otherwise CVODES integrates.
#pragma once

#include <memory>
#include <vector>

#include "models/axis.h"

namespace driveid {

struct AxisResponse {
  std::vector<double> position, rate;  ///< q(t_k), v(t_k)
  /// d q(t_k) / d p_j and d v(t_k) / d p_j, row-major (sample k, parameter j).
  std::vector<double> position_sensitivity, rate_sensitivity;
  std::vector<int> mode;  ///< friction mode at t_k (-1, 0, +1)
  int switch_count = 0;
};

class AxisSimulator {
 public:
  /// `terms`: indices of the axis parameters (models/axis.h AxisTermRow)
  /// whose sensitivities Simulate computes. Absolute tolerances of q and v
  /// (of the integrator). While every term present is affine in the rate
  /// within a mode (models/axis_term.h mode_affine) the axis is solved
  /// exactly per held sample (no integrator) unless `allow_exact` is false.
  AxisSimulator(std::vector<int> terms, double position_tolerance, double rate_tolerance, bool allow_exact = true);
  ~AxisSimulator();
  AxisSimulator(const AxisSimulator&) = delete;
  AxisSimulator& operator=(const AxisSimulator&) = delete;

  /// Simulates from (q0, v0) at time[0]. Needs p.inertia > 0. Throws
  /// IdentificationError when the integrator fails or chatters.
  void Simulate(const AxisParameters& p, const std::vector<double>& time, const std::vector<double>& torque,
                double q0, double v0, bool with_sensitivities, AxisResponse* response);

 private:
  class System;
  std::unique_ptr<System> system_;
};

}  // namespace driveid
