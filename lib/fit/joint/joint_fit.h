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

#include "fit/core/least_squares.h"
#include "logs/joint_log.h"
#include "models/joint.h"

namespace driveid {

struct JointFitOptions {
  /// Empty: the default for the logs (JointDefaultFree).
  std::vector<std::string> free;
  double cutoff = 0.0;              ///< [Hz]; 0 = rate / 40
  double min_rate_fraction = 0.01;
  bool per_log = true;  ///< several logs: each fitted alone too, and tested for agreement
  /// The fit whose warnings are shown: also the same fit at half and twice the
  /// cutoff (adequacy.h ProcessingWarnings), the cutoff advice tried, and the
  /// shaft-torque location test (false: a per-log, trial or start fit).
  bool sensitivity = true;
  /// Name what the two-mass model lacks (fit/joint/joint_mismatch.h) even without
  /// `sensitivity` (an output-error fit's inverse-dynamics start).
  bool mismatch = false;
  /// false: estimates however uncertain (start values of an output-error fit).
  bool refuse_undetermined = true;
  FitOptions fit;
  /// Whether the values can be used (as AxisFitOptions': a negative cutoff
  /// is refused, not read as rate / 40); else `error` names the field and the constraint.
  bool IsValid(std::string* error) const;
};

/// The default free set: the table's (inertias, spring, friction, offset)
/// when a log has the motor torque, plus link_torque_offset when one has
/// tau_link; with tau_link only: stiffness, damping, link_torque_offset.
std::vector<std::string> JointDefaultFree(const std::vector<JointLog>& logs);

struct JointFitOutput {
  JointParameters params;
  FitResult fit;
  double cutoff = 0.0;
  double rate = 0.0;  ///< [Hz], the logs' sampling rate
  /// Used samples: time, measured target (n tau or tau_link), model, channel
  /// (0 motor, 1 total, 2 shaft torque) and log.
  std::vector<double> time, measured, model;
  std::vector<int> equation, log_index;
  std::vector<double> motor_angle;  ///< the motor shaft's angle at each used sample [rad] (q_motor)
};

/// Fits the free parameters jointly over all logs; fixed ones from `start`
/// (J_m, J_l, k, d, friction and offset must be given when fixed; gravity
/// terms count as 0). Needs joint.gear_ratio. Throws OptionError,
/// InputError, IdentificationError.
JointFitOutput FitJoint(const std::vector<JointLog>& logs, const JointSection& start, const JointFitOptions& options);

}  // namespace driveid
