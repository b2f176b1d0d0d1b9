// The rows of the axis IDIM-LS (docs/models.md#axis): rates and
// accelerations from the logged position (or a measured rate), the
// full-rate regressor columns (the model's terms, CalcAxisRegressors, then
// |q'| and t - t_mid) and the force through the same parallel-decimation filter,
// every `decimation`-th sample clear of velocity reversals. Shared by the
// fit (axis_fit.h) and the validation of a parameter file (validation.h).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "fit/core/linear_regression.h"
#include "logs/axis_log.h"

namespace driveid {

/// Rates and accelerations at the log's samples (valid: computed there);
/// rate_hz is the constant sampling rate, 0 for irregular sampling.
struct AxisDerivatives {
  std::vector<double> rate, acceleration;
  std::vector<char> valid;
  double rate_hz = 0.0;  // 0 for irregular sampling
};

/// The position low-pass of constant-rate logs (signal/butterworth.h):
/// kFlat, the sharpened Butterworth 3 H^2 - 2 H^3, for the axis rows, whose
/// torque only the decimation filter shapes (the plain filter's pass band
/// loses (f/fc)^4 of q'' at f: +0.56 % of J with the cutoff 3.6 x the
/// highest line, +0.007 % sharpened; docs/models.md#axis-cutoff-from-the-data); kButterworth, the
/// plain one, where the fit passes the torque through the same filter
/// (the joint's IDIM, fit/joint/joint_fit.h).
enum class AxisPositionFilter { kFlat, kButterworth };

/// Differentiates the position (or the measured rate) with the position
/// low-pass `cutoff_request` [Hz] (0: rate / 40). OptionError above Nyquist.
AxisDerivatives DifferentiateAxisLog(const AxisLog& log, double cutoff_request,
                                     AxisPositionFilter filter = AxisPositionFilter::kFlat);

/// The logs' motion frequency f_m = RMS(q') / (2 pi RMS(q - linear trend))
/// [Hz], the largest over the logs (exactly f for q = A sin(2 pi f t)).
double AxisMotionFrequency(const std::vector<AxisLog>& logs);

/// The lowest sampling rate of the logs [Hz] (the mean rate where irregular).
double AxisSamplingRate(const std::vector<AxisLog>& logs);
/// The highest position cutoff the logs' differentiation can use [Hz]: 0.4 x
/// the rate at a constant rate; on irregular stamps (a DataLog's jittered
/// 50 Hz) kAxisIrregularCutoffShare of the mean rate, so that the local
/// quadratic's window (half 0.5 / cutoff) holds 2.5 samples a side.
double AxisHighestCutoff(const std::vector<AxisLog>& logs);
inline constexpr double kAxisIrregularCutoffShare = 0.2;

/// The band the decimated samples keep [Hz]: the parallel decimation
/// filter's cutoff, 0.8 x rate / (2 x decimation) (decimation below 1 counts as 1).
double AxisDecimatedBand(double rate, int decimation);

/// Position cutoffs a fit or validation chooses from [Hz]:
/// kCutoffPerMotionFrequency x f_m x 2^k below the decimated band
/// 0.8 x rate / (2 x decimation), then that band; {rate / 40} for logs
/// that do not move; {} without a usable rate.
constexpr double kCutoffPerMotionFrequency = 5.0;
/// Of the candidates the fit (ChooseAxisCutoff) and the validation keep the
/// highest unless a lower one's mean squared residual is smaller by more
/// than this fraction (docs/models.md#axis-cutoff-from-the-data).
constexpr double kAxisLowerCutoffGain = 0.05;
std::vector<double> AxisCutoffCandidates(const std::vector<AxisLog>& logs, int decimation);
/// The fit's and the validation's choice among `candidates` (ascending):
/// walking down from the highest, a lower candidate replaces the one held
/// only if its `mean_square` residual is below (1 - kAxisLowerCutoffGain)
/// times the held one's. `mean_square` returns +inf for a candidate the
/// data refuse, which never wins; if every one is refused, the highest
/// (the band) is returned; 0 for no candidates.
double PickAxisCutoff(const std::vector<double>& candidates, const std::function<double(double)>& mean_square);

/// The diagnostic columns' names (never fitted: the adequacy checks'
/// candidates for direction-dependent friction and drift).
constexpr const char* kAxisAbsRateColumn = "|q'|";
constexpr const char* kAxisTimeColumn = "t - t_mid";

/// The column names: the axis table's model keys in order, then the two
/// diagnostic ones.
std::vector<std::string> AxisRowColumnNames();

/// Rows are left out within at least this many decimations of a sample
/// slower than the rate threshold (a reversal, where Coulomb friction steps
/// and may stick). The step the friction puts into q'' passes the position
/// filter and the decimation filter: AxisExclusionReach finds how far it
/// spreads. At the highest cutoff candidate, the decimated band
/// 0.8 x rate / (2 x decimation), the sharpened position filter and the
/// decimation filter leave 2.7 % of the step at 2 decimations, 0.81 % at 3
/// and 0.12 % at 4 (the plain filter 2.8 % and 0.13 % at 2 and 3); noise-free,
/// four sines under a position loop gave viscous +0.42 % with 3, -0.17 %
/// with 4 (docs/models.md#axis-exclusion).
constexpr int kAxisExclusionDecimations = 3;
/// What of the friction step the filter pair may leave at the reach.
constexpr double kAxisExclusionSettled = 0.003;
/// The same for irregular sampling, whose local-polynomial rates have a
/// kernel of their own (no Butterworth pair): the reach of 2 decimations it
/// has always had (3 moved UR10e J2's inertia from 11.3 +- 2.6 to
/// 9.7 +- 3.3 against 18.2, and took its processing warning away).
constexpr int kAxisExclusionDecimationsIrregular = 2;

/// The reach [samples] rows keep from a slow sample at `cutoff` [Hz] (0:
/// rate / 40, no lower than kAxisExclusionLowestCutoff of the decimated
/// band): on a constant-rate log (rate > 0) the last distance from a unit
/// step at which the sharpened position filter, then (decimation > 1) the
/// decimation filter, leave more than kAxisExclusionSettled of it, rounded
/// up to whole decimations and at least kAxisExclusionDecimations of them;
/// kAxisExclusionDecimationsIrregular decimations on irregular logs (rate 0).
int AxisExclusionReach(double rate, double cutoff, int decimation);
/// The shortest reach [samples]: kAxisExclusionDecimations decimations at a
/// constant rate (rate > 0), kAxisExclusionDecimationsIrregular otherwise.
int AxisShortestReach(double rate, int decimation);
/// BuildAxisRows shortens the reach to this share of the median stretch of
/// motion between slow stretches (whole decimations, no less than
/// kAxisExclusionDecimations of them): a log that reverses every 0.2 s at a
/// cutoff of 5 Hz keeps rows (the settled reach there is over 100 ms).
constexpr double kAxisExclusionShareOfMotion = 0.25;
/// The reach follows the cutoff down to this fraction of the decimated band.
constexpr double kAxisExclusionLowestCutoff = 0.5;

/// Which cutoff sets the reach: the rows' own (kAtCutoff: the fit), or
/// the decimated band's (kAtBand: the same rows,
/// near enough, at every cutoff candidate, so that their residuals compare).
enum class AxisReach { kAtCutoff, kAtBand };
/// The reach [samples] BuildAxisRows starts from on a log sampled at `rate`
/// [Hz] (0: irregular), before the share-of-motion cap: AxisExclusionReach
/// at `cutoff` (kAtCutoff) or at the decimated band (kAtBand). On an
/// irregular log (mean rate `mean_rate`) at least the local quadratic's half
/// window, 0.5 / cutoff, in samples plus one (whole decimations): a row no
/// nearer a reversal, a gap or an end than the window the rates came from.
int AxisRowReach(double rate, double cutoff, int decimation, AxisReach reach, double mean_rate = 0.0);
/// AxisRowReach of each log (its rate as the rows read it): two row builds
/// at one cutoff and timing whose reaches agree build the same rows.
std::vector<int> AxisRowReaches(const std::vector<AxisLog>& logs, double cutoff, int decimation, AxisReach reach);

struct AxisRows {
  LinearRegression regression;  ///< one channel per log ("path:tau")
  std::vector<double> time, measured;
  std::vector<int> log_index;
  std::string method;           ///< how rates were obtained
};

/// When the logged torque acts (docs/models.md#torque-timing). kSampled: the
/// value at the sample's instant (a measured current). kHeld: the command a
/// drive holds from its sample to the next (zero-order hold); the central
/// second difference of q at sample k integrates u_(k-1) and u_k for half
/// each, (q_(k+1) - 2 q_k + q_(k-1)) / h^2 = (u_(k-1) + u_k) / (2 J) for an
/// inertia, so row k takes (u_(k-1) + u_k) / 2. kFromData: FitAxis reads it
/// from the data among kDelayed -0.5, 0 and +0.5 (docs/models.md#torque-timing).
/// kDelayed: the logged torque acts `delay`
/// samples after its stamp (a fraction in [-1, 1]: 0 sampled, +0.5 held, -0.5
/// a command held since the last sample, as ros2_control logs it); row k
/// takes the two-sample mean (u_(k-1) + u_k) / 2, which acts at
/// t_k + (delay - 0.5) h, against the regressors interpolated linearly to
/// that instant, so every delay fits the same dependent column and their
/// costs compare (kFromData estimates the delay so: FitAxis).
enum class AxisTorqueTiming { kSampled, kHeld, kFromData, kDelayed };

/// Largest |delay| of kDelayed [samples].
inline constexpr double kMaxTorqueDelay = 1.0;

/// The timing's name as the options and outputs spell it: sampled, held, auto.
const char* AxisTorqueTimingName(AxisTorqueTiming timing);
/// The names of `timings`, in their order (the choices an option offers).
std::vector<std::string> AxisTorqueTimingNames(const std::vector<AxisTorqueTiming>& timings);
/// The timing a name spells (AxisTorqueTimingName's inverse for sampled,
/// held, auto); OptionError naming ‹torque-timing› for any other.
AxisTorqueTiming AxisTorqueTimingFromName(const std::string& name);
/// As AxisTorqueTimingFromName, and a number in [-1, 1] (samples) spells
/// kDelayed with that `delay`.
AxisTorqueTiming ParseAxisTorqueTiming(const std::string& text, double& delay);
/// "sampled", "held", or "delay +0.37 samples" for kDelayed.
std::string DescribeAxisTorqueTiming(AxisTorqueTiming timing, double delay);

/// The torque as row k sees it under `timing` (the first sample kept).
std::vector<double> TimedAxisTorque(const std::vector<double>& torque, AxisTorqueTiming timing);

/// Builds the rows over all logs; `column_names` names the columns in the
/// order above (AxisRowColumnNames). InputError for a log shorter than kMinAxisLogSamples.
AxisRows BuildAxisRows(const std::vector<AxisLog>& logs, double cutoff, int decimation, double min_rate_fraction,
                       const std::vector<std::string>& column_names,
                       AxisTorqueTiming timing = AxisTorqueTiming::kSampled, AxisReach reach = AxisReach::kAtCutoff,
                       double torque_delay = 0.0);

}  // namespace driveid
