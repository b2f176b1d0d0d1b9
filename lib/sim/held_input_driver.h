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

/// The loop over samples 1 .. N-1 (sample 0 is the caller's: initial state,
/// input, Record(0)), resumable: RunTo records samples up to a given one and
/// the next call goes on from there (a long log simulated in pieces).
/// `time` and `input` must outlive it; `what` names the model in messages
/// ("drive train", "axis").
class HeldInputRun {
 public:
  HeldInputRun(CvodesIntegrator& integrator, const std::vector<double>& time, const std::vector<double>& input,
               HeldInputSystem& system, const char* what);
  /// Records the samples up to `last` (at most N-1) not recorded yet.
  void RunTo(std::size_t last);
  /// The next sample RunTo records.
  std::size_t next() const { return next_; }
  /// Mode switches so far.
  int switches() const { return switches_; }

 private:
  CvodesIntegrator& integrator_;
  const std::vector<double>& time_;
  const std::vector<double>& input_;
  HeldInputSystem& system_;
  const char* what_;
  long switch_budget_, step_budget_, steps_ = 0, last_count_ = 0;
  int switches_ = 0;
  std::size_t next_ = 1, end_ = 0;  // next sample; last sample of the current run of equal inputs
  bool in_run_ = false, integrating_ = false;
};

/// Runs samples 1 .. N-1 at once; returns the number of mode switches.
int RunHeldInput(CvodesIntegrator& integrator, const std::vector<double>& time, const std::vector<double>& input,
                 HeldInputSystem& system, const char* what);

}  // namespace driveid
