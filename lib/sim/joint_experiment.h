// Synthetic experiments on the elastic joint (docs/models.md#elastic-joint)
// for planning a frequency-response measurement (`drivetrain-fit simulate
// joint`): an excitation torque (multisine, chirp or PRBS) on the motor
// shaft, optionally injected after a PI speed loop on the measured motor
// speed, held per sample. Integrated with classic RK4 sub-steps; Coulomb
// friction sticks (Karnopp: a mass whose speed crosses zero, or is zero,
// while the other forces stay within its Coulomb level is held at rest).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "logs/joint_log.h"
#include "models/joint.h"

namespace driveid {

struct JointExperiment {
  std::string excitation = "multisine";  ///< multisine, chirp, prbs, or reference (the samples below)
  double rate = 1000.0;       ///< [Hz]
  double duration = 30.0;     ///< [s]
  double period = 2.0;        ///< [s] multisine period, chirp sweep, PRBS sequence (rounded to whole samples)
  double f_low = 0.5, f_high = 50.0;  ///< excited band [Hz]
  double amplitude = 0.1;     ///< rms of the excitation [N m, motor shaft]
  double kp = 0.0, ki = 0.0;  ///< PI speed loop on qd_motor [N m s/rad, N m/rad]; 0, 0: open loop
  double noise = 0.0;         ///< std of the motor-speed measurement noise [rad/s]
  std::uint64_t seed = 1;
  int substeps = 10;
  /// The "reference" excitation: torque samples at `rate`, repeated over
  /// the duration (`design joint` writes them; logs/torque_reference.h).
  std::vector<double> reference;
};

/// Throws OptionError naming a bad option.
JointExperimentLog SimulateJointExperiment(const JointParameters& params, double gear_ratio,
                                           const JointExperiment& experiment);

}  // namespace driveid
