// The rows of the axis IDIM-LS (docs/models.md#axis): rates and
// accelerations from the logged position (or a measured rate), the
// full-rate regressor columns (the model's terms, CalcAxisRegressors, then
// |q'| and t - t_mid) and the force through the same parallel-decimation filter,
// every `decimation`-th sample clear of velocity reversals. Shared by the
// fit (axis_fit.h) and the validation of a parameter file (validation.h).
#pragma once

#include <string>
#include <vector>

#include "fit/linear_regression.h"
#include "io/axis_log.h"

namespace driveid {

/// Rates and accelerations at the log's samples (valid: computed there);
/// rate_hz is the constant sampling rate, 0 for irregular sampling.
struct AxisDerivatives {
  std::vector<double> rate, acceleration;
  std::vector<char> valid;
  double rate_hz = 0.0;  // 0 for irregular sampling
};

/// Differentiates the position (or the measured rate) with the position
/// low-pass `cutoff_request` [Hz] (0: rate / 40). OptionError above Nyquist.
AxisDerivatives DifferentiateAxisLog(const AxisLog& log, double cutoff_request);

/// The logs' motion frequency f_m = RMS(q') / (2 pi RMS(q - linear trend))
/// [Hz], the largest over the logs (exactly f for q = A sin(2 pi f t)).
double AxisMotionFrequency(const std::vector<AxisLog>& logs);

/// The lowest sampling rate of the logs [Hz] (the mean rate where irregular).
double AxisSamplingRate(const std::vector<AxisLog>& logs);

/// The band the decimated samples keep [Hz]: the parallel decimation
/// filter's cutoff, 0.8 x rate / (2 x decimation) (decimation below 1 counts as 1).
double AxisDecimatedBand(double rate, int decimation);

/// Position cutoffs a fit or validation chooses from [Hz]:
/// kCutoffPerMotionFrequency x f_m x 2^k below the decimated band
/// 0.8 x rate / (2 x decimation), then that band; {rate / 40} for logs
/// that do not move; {} without a usable rate.
constexpr double kCutoffPerMotionFrequency = 5.0;
std::vector<double> AxisCutoffCandidates(const std::vector<AxisLog>& logs, int decimation);

/// The diagnostic columns' names (never fitted: the adequacy checks'
/// candidates for direction-dependent friction and drift).
constexpr const char* kAxisAbsRateColumn = "|q'|";
constexpr const char* kAxisTimeColumn = "t - t_mid";

/// The column names: the axis table's model keys in order, then the two
/// diagnostic ones.
std::vector<std::string> AxisRowColumnNames();

/// Rows are left out within this many decimations of a sample slower than
/// the rate threshold (a reversal, where Coulomb friction steps and may
/// stick). The step the friction puts into q'' passes the position filter
/// and the decimation filter; at the highest cutoff candidate (the
/// decimated band, both filters a zero-phase second-order Butterworth at
/// 0.8 x rate / (2 x decimation)) the pair leaves 2.8 % of the step at 2
/// decimations, 0.13 % at 3 (under 0.3 % beyond 2.6): 2 biased the inertia
/// of a noise-free designed tracking log by -0.07 %, 3 by -0.01 %
/// (docs/models.md#axis-exclusion). A lower cutoff spreads the step
/// further: the processing-sensitivity check (axis_fit.h) names what moves.
constexpr int kAxisExclusionDecimations = 3;
/// The same for irregular sampling, whose local-polynomial rates have a
/// kernel of their own (no Butterworth pair): the reach of 2 decimations it
/// has always had (3 moved UR10e J2's inertia from 11.3 +- 2.6 to
/// 9.7 +- 3.3 against 18.2, and took its processing warning away).
constexpr int kAxisExclusionDecimationsIrregular = 2;

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
/// inertia, so row k takes (u_(k-1) + u_k) / 2. kFromData: whichever of
/// the two leaves the smaller residual (FitAxis; docs/models.md#torque-timing).
/// kSampledSmoothed: the sampled reading with the torque and every regressor
/// column through the held reading's two-sample mean, so that both readings
/// fit the same dependent column (the from-data choice compares their costs).
enum class AxisTorqueTiming { kSampled, kHeld, kFromData, kSampledSmoothed };

/// The timing's name as the options and outputs spell it: sampled, held, auto.
const char* AxisTorqueTimingName(AxisTorqueTiming timing);
/// The timing a name spells (AxisTorqueTimingName's inverse for sampled,
/// held, auto); OptionError naming ‹torque-timing› for any other.
AxisTorqueTiming AxisTorqueTimingFromName(const std::string& name);

/// The torque as row k sees it under `timing` (the first sample kept).
std::vector<double> TimedAxisTorque(const std::vector<double>& torque, AxisTorqueTiming timing);

/// Builds the rows over all logs; `column_names` names the columns in the
/// order above (AxisRowColumnNames). InputError for a log shorter than kMinAxisLogSamples.
AxisRows BuildAxisRows(const std::vector<AxisLog>& logs, double cutoff, int decimation, double min_rate_fraction,
                       const std::vector<std::string>& column_names,
                       AxisTorqueTiming timing = AxisTorqueTiming::kSampled);

}  // namespace driveid
