// Identification of the elastic joint (docs/models.md#elastic-joint) by
// inverse dynamics from logged motor and link angles and the motor torque:
// both angles referred to the link side and low-passed zero-phase at
// `cutoff` (default rate / 40), central-difference rates and accelerations,
// the torque and the deflection through the same filter; two channels per
// log, the motor equation and the total (motor + link) equation, each with
// n tau as its target (models/joint.h), stacked and solved by the shared
// linear fit core (robust covariance, identifiability on the Jacobian).
// Samples where a rate that carries a Coulomb term is below
// min_rate_fraction of its largest value are left out of that equation.
// A free inertia, stiffness, damping or friction whose robust std exceeds
// 50 % of its value is refused by name (adequacy.h).
#pragma once

#include <string>
#include <vector>

#include "fit/least_squares.h"
#include "io/joint_log.h"
#include "models/joint.h"

namespace driveid {

struct JointFitOptions {
  std::vector<std::string> free = FitParameterKeys(JointParameterTable(), "joint", true);
  double cutoff = 0.0;              ///< [Hz]; 0 = rate / 40
  double min_rate_fraction = 0.01;
  FitOptions fit;
};

struct JointFitOutput {
  JointParameters params;
  FitResult fit;
  double cutoff = 0.0;
  /// Used samples: time, measured n tau, model, channel (0 motor, 1 total) and log.
  std::vector<double> time, measured, model;
  std::vector<int> equation, log_index;
};

/// Fits the free parameters jointly over all logs; fixed ones from `start`
/// (J_m, J_l, k, d, friction and offset must be given when fixed; gravity
/// terms count as 0). Needs joint.gear_ratio. Throws OptionError,
/// InputError, IdentificationError.
JointFitOutput FitJoint(const std::vector<JointLog>& logs, const JointSection& start, const JointFitOptions& options);

}  // namespace driveid
