// Simulation of the drive train of models/drivetrain.h under a zero-order-
// hold motor torque, with Coulomb friction that truly sticks, and forward
// sensitivities of the link torque with respect to chosen parameters.
//
// Stick/slip is a switched system. Each friction mode (-1, 0, +1) has a
// smooth vector field, linear in the state and the torque, so each sample
// interval is solved exactly (sim/switched_linear_exact.h: matrix
// exponentials, events located on the exact solution). CVODES (events by
// its root finding, restarted at every change of the torque) is the
// alternative integration; both agree to its tolerance
// (tests/sim/drivetrain_simulator_test.cc). Modes and events:
//   sliding (mode +-1): root g = omega. At omega = 0 the drive sticks if
//     |F| <= tau_c, else it reverses (mode = sgn F).
//   stuck (mode 0): roots g = F - tau_c and g = F + tau_c; crossing one
//     breaks the drive away in the direction of F.
// At a state event at t*(p) where the field jumps from f- to f+, the
// sensitivities jump by
//   s+ = s- + (f- - f+) dt*/dp,  dt*/dp = -(dg/dx s-) / (dg/dx f-)
// (differentiate x(t*(p), p) on both sides of the event). For sticking this
// gives s_omega+ = 0; at a reversal s_omega+ = s_omega- f+_omega / f-_omega;
// at a break-away f is continuous (F = +-tau_c there) and nothing jumps.
// Input steps happen at sample times, which do not depend on p: the field
// jumps but the sensitivities do not.
//
// The torque command tau_motor[k] is held on [t_k, t_{k+1}); the response
// y_k = tau_link(t_k) is sampled before the new command applies. The drive
// starts at rest and unloaded at t_0 (phi = Delta = 0).
// Documented in docs/models.md#drive-train.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "models/drivetrain.h"

namespace driveid {

/// Simulated response at the sample times.
struct DriveTrainResponse {
  std::vector<double> link_torque;              ///< tau_link(t_k) [N m]
  /// d tau_link(t_k) / d p_j, row-major (sample k, parameter j); empty without sensitivities.
  std::vector<double> link_torque_sensitivity;
  std::vector<double> motor_angle;              ///< phi(t_k) [rad, gear output side]
  std::vector<double> deflection;               ///< Delta(t_k) [rad], the link root angle
  /// d phi(t_k) / d p_j and d Delta(t_k) / d p_j (as link_torque_sensitivity).
  std::vector<double> motor_angle_sensitivity, deflection_sensitivity;
  std::vector<int> friction_mode;               ///< friction mode at t_k (-1, 0, +1)
  int switch_count = 0;                         ///< number of stick/slip switches
};

/// Integrator accuracy. The defaults resolve the link torque far below any
/// strain-gauge noise; tighter values are for checking derivatives.
struct SimulationTolerances {
  double relative = 1e-7;     ///< relative tolerance of states and sensitivities
  double link_torque = 1e-6;  ///< absolute tolerance, expressed as link torque [N m]
};

/// How a run is integrated: exactly per sample interval (the default), or
/// by CVODES (restarted at every change of the torque; kept to check the
/// exact path against and for comparisons).
enum class DriveTrainIntegration { kExact, kCvodes };

class DriveTrainSimulator {
 public:
  /// `nominal` sets the integrator's tolerance scales; `sensitivity_parameters`
  /// are the parameters whose sensitivities Simulate can compute.
  DriveTrainSimulator(DriveTrainModel model, const DriveTrainParameters& nominal,
                      std::vector<DriveTrainParameter> sensitivity_parameters,
                      const SimulationTolerances& tolerances = {});
  ~DriveTrainSimulator();
  DriveTrainSimulator(const DriveTrainSimulator&) = delete;
  DriveTrainSimulator& operator=(const DriveTrainSimulator&) = delete;

  /// Simulates the response to the held torque command. `time` strictly
  /// increasing, same length as `motor_torque`. Reuses `response`'s storage.
  /// Throws IdentificationError if the integrator fails.
  void Simulate(const DriveTrainParameters& params, const std::vector<double>& time,
                const std::vector<double>& motor_torque, bool with_sensitivities, DriveTrainResponse* response);

  /// The same in pieces, for logs whose whole response would not fit in
  /// memory beside the solver's Jacobian: Start sets up the simulation
  /// (`time` and `motor_torque` must stay alive and unchanged while it runs),
  /// each Advance simulates the samples from next_sample() up to `last` and
  /// leaves only those in `response` (its index 0 is sample next_sample()
  /// before the call). Advance throws IdentificationError if the integrator
  /// fails; the simulation must then be started again.
  void Start(const DriveTrainParameters& params, const std::vector<double>& time,
             const std::vector<double>& motor_torque, bool with_sensitivities);
  void Advance(std::size_t last, DriveTrainResponse* response);
  std::size_t next_sample() const;

  /// Whether responses hold the angles phi, Delta, their sensitivities and
  /// the friction mode (default); without, they stay empty (a fit of
  /// tau_link alone saves five of the response's seven arrays).
  void set_record_angles(bool record);
  /// The integration of the next Start (default kExact).
  void set_integration(DriveTrainIntegration integration);

  DriveTrainModel model() const;
  const std::vector<DriveTrainParameter>& sensitivity_parameters() const;

 private:
  class System;
  std::unique_ptr<System> system_;
};

}  // namespace driveid
