// Inverse-dynamics identification of a rigid axis (docs/models.md#axis) by IDIM-LS:
//   1. zero-phase low-pass of the position (the sharpened Butterworth
//      3 H^2 - 2 H^3, flat in its pass band, signal/butterworth.h), cutoff
//      `cutoff` (default from the data: of multiples of the motion
//      frequency, the highest unless a lower one's residual is 5 % smaller,
//      ChooseAxisCutoff), and the same fit at half and twice the cutoff: an
//      estimate that moves by more than 2 std draws a warning;
//   2. central-difference velocity and acceleration;
//   3. parallel decimation: the regressor columns [q'', q', sgn(q'), 1] and
//      the measured force pass the same zero-phase low-pass at 0.8 of the
//      decimated Nyquist frequency, then every `decimation`-th sample is kept
//      (default 10: the information lies below the position cutoff);
//   4. bounded least squares through the shared fit core (standard errors,
//      identifiability), relative error of the fit |tau - X p| / |tau|.
// Samples near a velocity reversal (|q'| below min_rate_fraction of the
// largest rate, anywhere within the filters' reach, AxisExclusionReach) are left out.
// The torque's timing (held command or sampled value, fit/axis/axis_rows.h) is
// given or chosen from the data (kFromData: the smaller residual at twice
// the decimated band; a warning names the estimates an unclear choice moves).
// Irregularly sampled logs are differentiated with the local-polynomial
// differentiator instead of the Butterworth path (no constant rate assumed).
// Identifiability comes from the data: the Jacobian's near-null directions
// and, for a free J, b or tau_c, the robust relative std (adequacy.h). The
// adequacy checks warn of a term the residuals ask for (gravity, the
// inertia when fixed, direction-dependent friction, drift), a low fit and
// logs that disagree (fit.warnings, docs/models.md#adequacy).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "fit/core/adequacy.h"
#include "fit/axis/axis_rows.h"
#include "fit/core/least_squares.h"
#include "logs/axis_log.h"
#include "models/axis.h"

namespace driveid {




/// The end of the processing warning's advice where the rate was measured
/// (output error does not differentiate); the identification run tries it
/// and says what it gives right after it (workflow/axis_identification.cc).
inline constexpr const char* kAxisOutputErrorAdvice = "‹method› oe, which does not differentiate";

/// The axis fit's largest default decimation after its parallel filtering:
/// every 10th sample kept of a kHz log (docs/models.md#axis-decimation),
/// declared once for the fit, the workflow and the tools.
inline constexpr int kAxisDecimation = 10;
/// The decimation by default: chosen from the logs (ChooseAxisDecimation).
inline constexpr int kAxisDecimationFromLogs = 0;
/// ChooseAxisDecimation keeps the decimated rate at or above this [Hz]...
inline constexpr double kAxisDecimatedRate = 100.0;
/// ... and at least this many rows of the shortest log.
inline constexpr int kAxisRowsPerLog = 40;

struct AxisFitOptions {
  std::vector<std::string> free = FitParameterKeys(AxisParameterTable(), "axis", true);
  double cutoff = 0.0;                ///< position low-pass [Hz]; 0 = ChooseAxisCutoff
  bool sensitivity = true;            ///< also fit at half and twice the cutoff
  /// Keep every n-th sample after parallel filtering; kAxisDecimationFromLogs:
  /// ChooseAxisDecimation.
  int decimation = kAxisDecimationFromLogs;
  AxisTorqueTiming torque_timing = AxisTorqueTiming::kSampled;  ///< fit/axis/axis_rows.h; kFromData: FitAxis estimates
  double torque_delay = 0.0;          ///< kDelayed: when the torque acts after its stamp [samples, -1 .. 1]
  double min_rate_fraction = 0.01;    ///< exclude |q'| below this fraction of max |q'|
  double max_relative_std = kMaxRelativeStd;  ///< refuse a free J, b or tau_c less certain than this
  bool per_log = true;                ///< with several logs, also fit each alone and compare
  FitOptions fit;
  /// Whether the values can be used; else `error` names the field and the constraint.
  bool IsValid(std::string* error) const;
};
/// The defaults with the torque's timing found from the data (kFromData):
/// what the identification runs by default (workflow/axis_identification.h).
inline AxisFitOptions AxisFitOptionsFromData() {
  AxisFitOptions o;
  o.torque_timing = AxisTorqueTiming::kFromData;
  return o;
}

struct AxisFitOutput {
  AxisParameters params;
  FitResult fit;
  double relative_error_percent = 0.0;  ///< |tau - X p| / |tau| on the decimated samples
  double acceleration_content = 0.0;    ///< RMS(q'') / RMS(q') [1/s] of the used samples
  /// The rate's spread about each log's mean over its RMS, pooled over the
  /// used samples (0: every log at a constant rate).
  double rate_variation = 0.0;
  std::string method;                   ///< how rates were obtained
  double cutoff = 0.0;
  std::string cutoff_rule;                        ///< how the cutoff was chosen
  int decimation = 1;                             ///< the decimation used
  std::string decimation_rule;                    ///< how it was chosen
  AxisTorqueTiming torque_timing = AxisTorqueTiming::kSampled;  ///< the reading used (never kFromData)
  double torque_delay = 0.0;      ///< kDelayed: the delay used [samples]
  std::string timing_rule;                        ///< how it was chosen
  int samples_used = 0;
  std::vector<double> time, measured, model;  ///< decimated samples used, for traces and plots
  std::vector<int> log_index;
};

/// The default position cutoff [Hz], from the data: candidates
/// kCutoffPerMotionFrequency x 2^k x the logs' motion frequency
/// f_m = RMS(q') / (2 pi RMS(q - trend)), up to the decimated band
/// 0.8 x rate / (2 x decimation); the fit at each, scored on the rows the
/// band's reach keeps, and the highest cutoff unless a lower one's fit leaves
/// a mean squared torque residual 5 % smaller (rate / 40 for logs that do
/// not move; docs/models.md#axis-cutoff-from-the-data).
double ChooseAxisCutoff(const std::vector<AxisLog>& logs, const AxisSection& start, const AxisFitOptions& options);

/// The default decimation (docs/models.md#axis-decimation): the largest
/// factor up to kAxisDecimation that keeps the logs' lowest rate at or above
/// kAxisDecimatedRate once decimated and kAxisRowsPerLog rows of the
/// shortest log: every sample of a 50 Hz SysIdRoutine log, every 2nd of a
/// 200 Hz SysId file, every 10th of a kHz log. `rule` says which bound set it.
int ChooseAxisDecimation(const std::vector<AxisLog>& logs, std::string* rule);
/// `requested` when given (> 0; `rule` "given"), else ChooseAxisDecimation.
int AxisDecimationFor(const std::vector<AxisLog>& logs, int requested, std::string* rule);

/// Logs slower than 2 x kAxisDecimatedRate whose stamps jitter about a
/// constant step (a DataLog's 20 ms loop: every interval below 2.5 mean
/// steps, no more than 5 % of them off it by more than half), resampled
/// onto that step by linear interpolation, so
/// that the parallel filter and central differences apply; logs with gaps
/// or measured-row flags are kept as they are (local polynomials). `notes`
/// says which were resampled (docs/models.md#axis-decimation). Returns
/// `logs` itself when none is resampled (no copy), else `storage` filled.
const std::vector<AxisLog>& UniformAxisLogs(const std::vector<AxisLog>& logs, std::vector<AxisLog>& storage,
                                            std::vector<std::string>* notes);

/// One model parameter of a fit: free (with its start value) or fixed.
struct ResolvedAxisTerm {
  std::string key;
  std::size_t index = 0;  ///< parameter index: AxisTermRow; < AxisLinearCount(): CalcAxisRegressors
  bool free = false;
  double value = 0.0;     ///< start value if free, else the fixed value
};

/// The terms of a fit with free set `free` (table order): refuses a term with
/// its direction-dependent replacement (OptionError) and a fixed J's
/// siblings b, tau_c, tau_0 not given (InputError); fixed terms not given
/// (J, the others, the replaced ones) count as 0.
std::vector<ResolvedAxisTerm> ResolveAxisTerms(const AxisSection& start, const std::vector<std::string>& free);

/// The fit at options.cutoff (> 0), without the sensitivity fits.
AxisFitOutput FitAxisAtCutoff(const std::vector<AxisLog>& logs, const AxisSection& start,
                              const AxisFitOptions& options);

/// Fits the free parameters jointly over all logs; fixed ones come from `start`.
/// Start values and fixed values come from `start` (a fixed parameter other
/// than the inertia must be given).
AxisFitOutput FitAxis(const std::vector<AxisLog>& logs, const AxisSection& start, const AxisFitOptions& options);

}  // namespace driveid
