// The sample loop shared by the simulators of switched (stick/slip) systems
// under an input held between samples (sim/drivetrain_simulator.h,
// sim/axis_simulator.h): per run of equal inputs, set the input (which may
// decide the friction mode at rest), integrate with CVODES up to each
// sample unless the system is frozen (stuck without dynamics: its state and
// sensitivities stay constant), handle every root the integrator stops at
// (a mode switch), and record each sample. Budgets of switches and
// integrator steps per sample make a pathological trial point of a solver
// (near-zero inertia, chattering) fail fast with IdentificationError.
#pragma once

#include <cstddef>
#include <vector>

#include "sim/cvodes_integrator.h"

namespace driveid {

/// What the loop asks of a simulator; the with-sensitivities choice lives
/// in the implementation.
class HeldInputSystem {
 public:
  virtual ~HeldInputSystem() = default;
  /// The input held from now on; decide the mode if the system is at rest.
  virtual void SetInput(double input) = 0;
  /// True while the state cannot change (stuck without dynamics).
  virtual bool Frozen() const = 0;
  /// Restart the integrator at t from the current state.
  virtual void Restart(double t) = 0;
  /// A root stopped the integrator: take its state, switch the mode, apply
  /// the sensitivity jump conditions.
  virtual void HandleSwitch() = 0;
  /// Take the integrator's state (and sensitivities) at a sample.
  virtual void CopyFromIntegrator() = 0;
  /// Store sample k.
  virtual void Record(std::size_t k) = 0;
};

/// Runs samples 1 .. N-1 (sample 0 is the caller's: initial state, input,
/// Record(0)). `what` names the model in messages ("drive train", "axis").
/// Returns the number of mode switches.
int RunHeldInput(CvodesIntegrator& integrator, const std::vector<double>& time, const std::vector<double>& input,
                 HeldInputSystem& system, const char* what);

}  // namespace driveid
