// `drivetrain-fit gains` for a rigid axis: LQR feedback gains from the
// feed-forward model Kv, Ka (control/feedback_gains.h) with the conventions
// of a controller preset, their standard errors from the parameter file's
// covariance (docs/models.md#feedback-gains).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "control/feedback_gains.h"
#include "control/speed_loop.h"
#include "params/parameter_file.h"
#include "models/feedback.h"
#include "report/feedback_report.h"
#include "report/json.h"
#include "report/plot.h"

namespace driveid {

struct AxisGainsOptions {
  std::string loop = "velocity";  ///< velocity | position
  std::string preset = "wpilib";  ///< control/feedback_gains.h ControllerPresets()
  std::optional<double> period;   ///< [s], else the preset's
  std::optional<double> delay;    ///< [s], else the preset's (velocity measurement delay)
  /// The LQR's weights [position unit, position unit/s, effort unit]; 0:
  /// SysIdWeights (as SysId's GUI sets them, docs/models.md#feedback-gains).
  double max_position_error = 0.0;
  double max_velocity_error = 0.0;
  double max_effort = 7.0;
  /// Controller position units per parameter-file position unit; 0: from
  /// the preset's unit (rotations from an angle unit; 1 for wpilib).
  double conversion = 0.0;
  std::optional<double> kv, ka;   ///< given values (no file, or overriding it)
  double kv_std = 0.0, ka_std = 0.0;
  /// Every bound on these fields (‹field› names the option); see core/option_check.h.
  bool IsValid(std::string* error) const;
};

/// SysId's LQR weights. Its settings' defaults (sysid/analysis/AnalysisManager.h,
/// `LQRParameters lqr{1, 1.5, 7}`): what it uses with no data loaded, and
/// driveid with Kv and Ka given by hand. On loading data its GUI replaces the
/// first two (allwpilib sysid/src/main/native/cpp/view/Analyzer.cpp,
/// Analyzer::ConfigParamsOnFileSelect): the maximum position error 0.1 of
/// the data's unit, and the maximum velocity error a quarter of the top
/// speed, (12 V - Ks) / (4 Kv); driveid does the same for a fit in volts.
inline constexpr double kSysIdMaxPositionError = 1.0, kSysIdMaxVelocityError = 1.5, kSysIdMaxEffort = 7.0;
inline constexpr double kSysIdLoadedPositionError = 0.1, kSysIdBatteryVolts = 12.0;

struct AxisGainsDesign {
  FeedbackController controller;
  std::string kv_source;          ///< where Kv and Ka came from, for the report
  double kv = 0.0, kv_std = 0.0, ka = 0.0, ka_std = 0.0, correlation = 0.0;
  std::optional<double> ks;       ///< the file's Ks (feed-forward section), for SysId's weights
  std::vector<std::string> notes;
  std::vector<std::string> warnings;  ///< e.g. a gain the delay makes useless
};

/// `file` may be null when Kv and Ka are given. InputError for a file with
/// neither a feed-forward nor an axis section, IdentificationError (exit 4)
/// for Ka <= 0 or Kv < 0 estimates, OptionError for bad settings.
AxisGainsDesign DesignAxisGains(const ParameterFile* file, const std::string& path, const AxisGainsOptions& options);
/// The plant the gains came from, as `gains` prints it: one line of text, and
/// {source, kv: {value, std}, ka: {value, std}, correlation}.
std::string FormatAxisGainsPlant(const AxisGainsDesign& design);
Json AxisGainsPlantJson(const AxisGainsDesign& design);


}  // namespace driveid

namespace driveid {

struct JointGainsOptions {
  double period = 0.001;           ///< [s]; the loop's delay is the drive's + 1.5 periods
  /// The drive's delay from the torque command to the measured speed [s];
  /// else the file's fitted `delay` (frf), else none.
  std::optional<double> delay;
  double phase_margin_deg = 50.0;
  double notch_width_hz = 0.0;     ///< 0: from the resonance's uncertainty
  /// Every bound on these fields (‹field› names the option); see core/option_check.h.
  bool IsValid(std::string* error) const;
};

struct JointGainsDesign {
  FeedbackController controller;
  std::vector<std::string> notes;
  SpeedLoopPlant plant;            ///< the identified model
  SpeedLoopDesign design;          ///< its controller C(s) and margins (met: otherwise refused)
  double period = 0.0;
};

/// The speed loop's plot: |L| [dB] and its phase with the margins, and the
/// closed loop's response to a unit speed step on the identified model.
std::vector<PlotPanel> SpeedLoopPanels(const JointGainsDesign& design);

/// A PI speed loop with a notch for the file's joint section
/// (control/speed_loop.h); the 95 % region from the fit's estimates and
/// correlation when the file has them. InputError without a joint section,
/// IdentificationError (exit 4) when no crossover meets the margins.
JointGainsDesign DesignJointGains(const ParameterFile& file, const std::string& path, const JointGainsOptions& options);

}  // namespace driveid
