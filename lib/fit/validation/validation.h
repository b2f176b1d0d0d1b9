// Validation (MATLAB's `compare`): predict logs from a parameter file and
// say how well the prediction matches (docs/models.md#validation).
//  - axis: inverse dynamics, the torque from the logged motion through the
//    same differentiation, filtering and decimation as the fit (axis_rows.h);
//  - step: simulation of the drive train from the logged motor torque
//    (CVODES, stick-slip), compared with the logged link torque;
//  - C-drive: inverse dynamics (28) of both motor torques from the angles;
//  - axis by simulation: the position simulated from the logged effort from
//    the logged start, by driveid's axis simulator (output error's, Coulomb
//    friction that sticks) or by MuJoCo from an exported MJCF.
// Per log: samples, RMSE, fit % and the residual lag-1 autocorrelation, and
// the measured and predicted series for plots and traces.
#pragma once

#include <string>
#include <vector>

#include "core/fit_result.h"
#include "fit/axis/axis_rows.h"
#include "fit/cdrive/cdrive_fit.h"
#include "logs/axis_log.h"
#include "logs/joint_log.h"
#include "logs/step_log.h"
#include "models/axis.h"
#include "models/drivetrain.h"
#include "sim/mujoco_axis_simulator.h"

namespace driveid {

struct ValidatedLog {
  ChannelStatistics stats;  ///< name "path:channel"; bandwidth 0, inflation 1
  std::vector<double> time, measured, model;
};

/// Fewest samples a validated log compares.
inline constexpr int kMinValidatedSamples = 3;

/// Refuses what is not a validation: a log without usable samples or with
/// fewer than kMinValidatedSamples (IdentificationError, exit 4, naming
/// it) or statistics that are not finite
/// (IdentificationError naming the log and the measured range). A fit % of a
/// channel that does not vary is NaN by design (ChannelStatistics) and passes.
void RequireValidated(const std::vector<ValidatedLog>& logs);

/// The axis logs predicted by `params` at the position cutoff `cutoff` [Hz]
/// (> 0; the fit's, or ChooseAxisValidationCutoff), `decimation` and the
/// torque's `timing` (fit/axis/axis_rows.h), on the rows clear of reversals by
/// `reach` (fit/axis/axis_rows.h AxisReach).
std::vector<ValidatedLog> ValidateAxis(const std::vector<AxisLog>& logs, const AxisParameters& params, double cutoff,
                                       int decimation, AxisTorqueTiming timing = AxisTorqueTiming::kSampled,
                                       AxisReach reach = AxisReach::kAtCutoff, double torque_delay = 0.0);

/// The cutoff for validating without a fit: the fit's rule
/// (ChooseAxisCutoff) on the prediction's residuals: of its candidates, the
/// highest unless a lower one's mean squared residual is kAxisLowerCutoffGain
/// smaller, each scored on the rows the band's reach keeps.
double ChooseAxisValidationCutoff(const std::vector<AxisLog>& logs, const AxisParameters& params, int decimation,
                                  AxisTorqueTiming timing = AxisTorqueTiming::kSampled, double torque_delay = 0.0);

/// The axis logs' positions simulated from their logged effort with `params`
/// (sim/axis_simulator.h), each from its start (fit/axis/axis_oe_fit.h's
/// AxisLogStart); "path:q". Needs params.inertia > 0.
std::vector<ValidatedLog> ValidateAxisBySimulation(const std::vector<AxisLog>& logs, const AxisParameters& params);

/// The same simulated in MuJoCo from the MJCF at `mjcf` (sim/mujoco_axis_simulator.h).
std::vector<ValidatedLog> ValidateMujocoAxis(const std::vector<AxisLog>& logs, const std::string& mjcf,
                                             const MujocoAxisOptions& options);

/// The elastic joint's logs simulated in MuJoCo from an MJCF as `export`
/// writes it (export/joint_export.h): the motor torque drives `joint`_motor
/// through its actuator (gear n), motor and link start at the logged angles
/// and rates (logged, else the slope of the first 10 samples); two entries
/// per log, "path:q_motor" (motor shaft, n x theta_m) and "path:q_link".
std::vector<ValidatedLog> ValidateMujocoJoint(const std::vector<JointLog>& logs, const std::string& mjcf,
                                              const std::string& joint, double max_step);

/// The C-drive logs' motor torques tau_L, tau_R predicted by inverse
/// dynamics (28) from the logged angles (two entries per log, "path:tau_L"
/// and "path:tau_R"), on the samples a friction fit would use.
std::vector<ValidatedLog> ValidateCDrive(const std::vector<CDriveLog>& logs, const CDriveParameters& params,
                                         const CDriveFitOptions& options);

/// The step logs simulated from their motor torque with `params`.
std::vector<ValidatedLog> ValidateSteps(const std::vector<StepLog>& logs, const DriveTrainParameters& params,
                                        DriveTrainModel model);

}  // namespace driveid
