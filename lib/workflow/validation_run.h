// What `drivetrain-fit validate` and `cdrive-fit validate` run (docs/models.md#validation,
// docs/export.md#validation-in-mujoco): which model a parameter file or an
// MJCF is validated as, and each validation with the words its outputs
// carry (method, plot title, unit). The command parses, loads the logs the
// model reads, calls one of these, emits.
#pragma once

#include <string>
#include <vector>

#include "fit/axis/axis_fit.h"
#include "fit/cdrive/cdrive_fit.h"
#include "fit/validation/validation.h"
#include "logs/axis_log.h"
#include "logs/cdrive_log.h"
#include "logs/joint_log.h"
#include "params/parameter_file.h"
#include "logs/step_log.h"
#include "models/drivetrain.h"
#include "report/plot.h"

namespace driveid {

enum class ValidationModel { kAxis, kStep, kJoint, kSerialRobot };

/// The model a validation runs: `requested` ("axis", "step", "joint",
/// "robot" for a serial robot; "" for the file's one model section); an MJCF (`mjcf`) is an axis unless
/// "joint" is asked for. Throws OptionError for a choice the file cannot
/// make (two sections, a joint from a parameter file, a step from an MJCF)
/// and InputError for a section the file lacks or an MJCF without MuJoCo;
/// `path` names the file.
ValidationModel ChooseValidationModel(const ParameterFile* file, bool mjcf, const std::string& path,
                                      const std::string& requested);

/// The validated logs and the words of their outputs.
struct ValidationRun {
  std::vector<ValidatedLog> logs;
  std::string method;  ///< how the prediction was made (the table's first line)
  std::string title;   ///< the plot's
  std::string unit;    ///< the plot's y label
};

struct AxisValidationOptions {
  bool simulate = false;  ///< simulate the position from the torque (else inverse dynamics of the torque)
  double cutoff = 0.0;    ///< inverse dynamics: position low-pass [Hz]; 0: the candidate that predicts best
  int decimation = kAxisDecimationFromLogs;  ///< 0: ChooseAxisDecimation on the logs validated
  AxisTorqueTiming torque_timing = AxisTorqueTiming::kSampled;  ///< inverse dynamics (fit/axis/axis_rows.h; not kFromData)
  double torque_delay = 0.0;  ///< kDelayed: when the torque acts after its stamp [samples]
  /// Take the timing the fit recorded (axis.torque_delay) when the file has it.
  bool timing_from_file = false;
  /// Every bound on these fields (‹field› names the option); see core/option_check.h.
  bool IsValid(std::string* error) const;
};
ValidationRun RunAxisValidation(const std::vector<AxisLog>& logs, const AxisSection& axis, const std::string& path,
                                const AxisValidationOptions& options);
ValidationRun RunStepValidation(const std::vector<StepLog>& logs, const DriveTrainSection& section,
                                DriveTrainModel model);
/// An MJCF in MuJoCo: an axis driven by the logged effort, or (joint) the
/// elastic joint's motor by the logged motor torque.
ValidationRun RunMujocoValidation(const std::vector<AxisLog>& logs, const std::string& mjcf, const std::string& joint,
                                  double max_step);
ValidationRun RunMujocoJointValidation(const std::vector<JointLog>& logs, const std::string& mjcf,
                                       const std::string& joint, double max_step);
/// `cdrive-fit validate`: both motor torques by inverse dynamics (28) from
/// the complete cdrive `section` (InputError naming `path` for a missing
/// value), the differentiator and sample selection of `prediction`.
ValidationRun RunCDriveValidation(const std::vector<CDriveLog>& logs, const CDriveSection& section,
                                  const std::string& path, const CDriveFitOptions& prediction);

/// What `validate` writes beside its table (docs/models.md#validation): the
/// trace CSV (log, t, measured, predicted, residual; `program` and `method`
/// in its header) and the plot's series, one per log.
struct ValidationOutputs {
  std::string trace_csv;
  std::vector<PlotSeries> series;
  std::vector<ChannelStatistics> stats;
};
ValidationOutputs AssembleValidationOutputs(const std::string& program, const std::string& method,
                                            const std::vector<ValidatedLog>& logs);

/// The quality gate (`‹fail_below›`): the logs whose fit % is below
/// `threshold` or has none, "name (x %)" each; empty when all pass.
std::vector<std::string> LogsBelowFit(const std::vector<ChannelStatistics>& stats, double threshold);

}  // namespace driveid
