// Synthetic step experiments in the step-log format (docs/formats.md#logs), from the same
// simulator the fit uses. Default: the paper's experiment (seed 000 Fig. 6),
// a motor torque step of -0.8 N m with joint B fixed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "logs/step_log.h"
#include "models/drivetrain.h"

namespace driveid {

struct StepExperiment {
  DriveTrainModel model = DriveTrainModel::kReduced;
  double rate = 1000.0;       ///< sampling rate [Hz]
  double duration = 0.2;      ///< [s]
  double step_time = 0.02;    ///< [s]
  double step_torque = -0.8;  ///< motor torque after the step [N m]
  double noise = 0.0;         ///< std of Gaussian noise on tau_link [N m]
  std::uint64_t seed = 1;     ///< noise seed
  double offset = 0.0;        ///< constant strain-gauge bias [N m]
};

/// Checks the experiment's settings; throws OptionError naming
/// the option, its value and the violated constraint.
void ValidateStepExperiment(const StepExperiment& experiment);

/// Simulates the experiment (noise and offset added to tau_link).
StepLog SimulateStepExperiment(const DriveTrainParameters& params, const StepExperiment& experiment);


}  // namespace driveid
