// Output-error identification of the elastic joint
// (docs/models.md#joint-output-error): simulate the two-mass joint from the
// logged motor torque (held between samples) with motor Coulomb friction
// that truly sticks (sim/joint_simulator.h), from the logged initial state
// (angles of the first sample; rates qd_motor, qd_link if logged, else the
// slope of the first 10 samples), and fit the free terms to the measured
// q_motor and q_link, to qd_motor and qd_link where logged and to the shaft
// torque tau_link where logged, jointly over all logs, through the shared
// fit core (robust covariance, identifiability). Two passes: the channels
// first weighted by 1 / RMS of their measured deviation from the mean, then
// by 1 / RMS of that fit's residuals (each channel counts by its noise).
// The link's Coulomb friction is not simulated: it must be 0.
// Multiple shooting (fit/joint/joint_oe_segments.h): each log is cut into
// segments simulated from their own fitted initial states, so that the noise
// of a measured torque drifts only over one segment; the intervals are then
// cluster-robust over the segments.
#pragma once

#include <string>
#include <vector>

#include "fit/joint/joint_oe_segments.h"
#include "fit/core/least_squares.h"
#include "logs/joint_log.h"
#include "models/joint.h"

namespace driveid {

struct JointOeOptions {
  /// Empty: JointOeDefaultFree.
  std::vector<std::string> free;
  bool per_log = true;  ///< several logs: each fitted alone too, and tested for agreement
  /// Segment length [s]: 0 auto (kSegmentResonancePeriods periods of the
  /// start values' resonance), infinite: the whole log (single shooting).
  double segment_seconds = 0.0;
  FitOptions fit;
  /// Every bound on these fields (‹field› names the option); see core/option_check.h.
  bool IsValid(std::string* error) const;
};

/// The inverse-dynamics default (JointDefaultFree) without link_coulomb.
std::vector<std::string> JointOeDefaultFree(const std::vector<JointLog>& logs);

struct JointOeOutput {
  JointParameters params;
  FitResult fit;
  /// Simulated q_motor and q_link per log, at the log's samples (log units).
  std::vector<std::vector<double>> motor_angle, link_angle;
  /// Per log: fit % of the deflection q_motor / n - q_link of the log
  /// simulated whole from its first segment's state (a warning below 80 %
  /// with correlated residuals).
  std::vector<double> deflection_fit_percent;
  /// Segments simulated (all logs) and their mean length [s].
  std::size_t segments = 0;
  double segment_seconds = 0.0;
};

/// Throws OptionError when link_coulomb is in `free` or nonzero in `start`.
void CheckOutputErrorSimulates(const JointSection& start, const std::vector<std::string>& free);

/// Fits the free terms; fixed ones from `start` (as FitJoint: J_m, J_l, k,
/// d, friction and offset must be given when fixed). `initial`: start values
/// of the free terms (e.g. the inverse-dynamics fit); an inertia or
/// stiffness <= 0 there starts from `start`. Needs joint.gear_ratio and the
/// motor torque in every log. Throws OptionError, InputError,
/// IdentificationError (naming the parameters).
JointOeOutput FitJointOutputError(const std::vector<JointLog>& logs, const JointSection& start,
                                  const JointParameters* initial, const JointOeOptions& options);

}  // namespace driveid
