// Checks every fit kind can run on its result (docs/models.md#adequacy):
//  - RequireDetermined: a free parameter with a physical lower bound of 0
//    (an inertia, a friction coefficient) whose robust standard error is
//    more than `max_relative_std` of its value is not determined by the
//    data: the fit refuses it by name (exit 4); one at its bound 0 is
//    reported there with a one-sided 95 % limit;
//  - low fit %: a channel whose fit is below kLowFitPercent with
//    correlated residuals;
//  - heterogeneity: the same parameters fitted per log disagree beyond
//    their uncertainties (Cochran's Q, I^2).
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/fit_result.h"

namespace driveid {

/// Bound on the robust relative standard error of a free non-negative parameter.
constexpr double kMaxRelativeStd = 0.5;
/// The one-sided 95 % quantile of the normal distribution.
constexpr double kOneSided95 = 1.6448536269514722;
/// A channel fitted below this percentage draws a warning, when its
/// residuals are correlated (lag-1 at least kLowFitMinAutocorrelation):
/// white residuals at a low fit % only say the channel hardly varies.
constexpr double kLowFitPercent = 50.0;
constexpr double kLowFitMinAutocorrelation = 0.3;
/// A measured channel whose std is below this fraction of its RMS (a
/// voltage step held constant, a constant-speed friction test) has no fit %:
/// it would compare the model with a constant that is as good.
constexpr double kNearlyConstant = 0.05;

/// Throws IdentificationError naming every free parameter with lower bound 0
/// (per `nonnegative`) whose standard error exceeds `max_relative_std` of
/// its magnitude. `context` is appended to the message (e.g. the warnings).
/// A parameter at its bound 0 with a finite std and a start value in
/// `start_values` is reported at the bound with its one-sided 95 % upper
/// limit (1.645 std) as its interval, and the fit stands: with a note
/// (FitResult::notes) when that limit lies within `max_relative_std` of the
/// start value or the start is 0 (the data rule out the magnitude it started
/// from), else with a warning (the data cannot tell 0 from the start).
void RequireDetermined(FitResult& fit, const std::vector<std::string>& nonnegative, double max_relative_std,
                       const std::vector<std::string>& context,
                       const std::map<std::string, double>& start_values = {});

/// The rule of a fit whose data may bound a non-negative parameter without
/// determining it (the axis fits; docs/models.md#adequacy), applied to the
/// final covariance (after any widening): a free parameter named in
/// `nonnegative` whose robust standard error exceeds `max_relative_std` of
/// its magnitude is
///  - an answer where the data bound it: its 95 % interval cut at 0,
///    [0, value + 1.96 std] ([0, 1.645 std], one-sided, at the bound 0),
///    with a warning "bounded only" naming it;
///  - refused by name (IdentificationError, exit 4) where the data say
///    nothing: its std not finite, or it is named in `silent` (the reason
///    said with it, e.g. an inertia of logs with no acceleration content).
/// `context` is appended to a refusal's message. Applied again, it gives the
/// same (an interval already cut is recomputed from the std).
void BoundOrRefuse(FitResult& fit, const std::vector<std::string>& nonnegative, double max_relative_std,
                   const std::vector<std::string>& context, const std::map<std::string, std::string>& silent = {});

/// RMSE, fit % = 100 (1 - |r| / |y - mean(y)|) (NaN for a channel that
/// does not vary or varies by less than kNearlyConstant of its RMS) and the
/// lag-1 autocorrelation of the residuals r = y - model of one channel
/// (`measured` may be null: fit % 0).
/// False when `count` measured values do not vary: their spread about the mean
/// is below 1e-9 of their largest magnitude (rounding), or zero.
bool MeasurementVaries(const double* measured, int count);

ChannelStatistics DescribeResiduals(const std::string& name, const double* measured, const double* residuals,
                                    int count);

/// One warning per channel fitted below kLowFitPercent.
std::vector<std::string> CheckFitPercent(const FitResult& fit);

/// Residual lag-1 autocorrelation above which a channel's residuals are
/// model error rather than noise: the long-run covariance's AR(1)
/// prewhitening stops at 0.99, and beyond it the intervals rest on a
/// handful of effective samples.
inline constexpr double kColouredResiduals = 0.99;

/// One warning per channel whose residual lag-1 exceeds kColouredResiduals,
/// naming the fit's parameters.
std::vector<std::string> CheckResidualColour(const FitResult& fit);

/// Tests each parameter of `logs` (where at least two logs estimated it).
std::vector<HeterogeneityTest> TestHeterogeneity(const std::vector<EstimateSet>& logs);

/// A processing move larger than this [%] of the estimate (and 2 std) is
/// warned of however well the estimate is determined.
inline constexpr double kProcessingPercent = 5.0;
/// A move to a higher cutoff (one that keeps more of the motion) of more
/// than this many std (the larger of the two fits') is warned of however
/// small in percent: the interval (1.96 std) cannot hold an error of that
/// size. Moves to lower cutoffs do not count here: there the filter
/// distorts the motion, which is why the cutoff search passed them over.
/// (A tracking log under a stiff position loop moved inertia by 7.6 std,
/// 0.5 %, at twice the cutoff while its estimate was 0.75 % = 11 std off,
/// with no warning under the 5 % rule alone; docs/models.md#adequacy.)
inline constexpr double kProcessingStds = 4.0;

/// Warnings for estimates that the same fit with other processing
/// (`fit.sensitivity`, e.g. half and twice the filter cutoff) moves by more
/// than 2 of their std and more than kProcessingPercent, or, at a higher
/// cutoff (EstimateSet::cutoff > `cutoff`), by more than kProcessingStds;
/// `cutoff` [Hz] the fit's own, `advice` what to try.
std::vector<std::string> ProcessingWarnings(const FitResult& fit, double cutoff, const std::string& advice);

/// The processing's spread in the covariance: where some estimate moves
/// with the processing (`fit.sensitivity`) by more than its std, each
/// alternative i (m of them) enters as a systematic error
/// g = (theta_i - theta) / sqrt(m), sigma 1 (AddSystematicCovariance): the
/// covariance of a choice among the candidates about the fit's own. Returns
/// whether it widened (a note says so in `fit.notes`).
bool WidenForProcessing(FitResult& fit, double cutoff);

/// Several logs: fits each alone through `fit_one(i)` (its estimates of the
/// shared parameters; an exception is recorded as that log's failure) into
/// fit.per_log labelled by `labels`, tests them for agreement
/// (fit.heterogeneity), widens the joint interval of a parameter on which
/// they disagree (p < 0.01; WidenForDisagreement) and adds a warning where
/// they disagree strongly (p < 0.001).
void AddPerLogFits(FitResult& fit, const std::vector<std::string>& labels,
                   const std::function<std::vector<ParameterEstimate>(std::size_t)>& fit_one);

/// The paths of logs, as labels of their per-log fits.
template <class Log>
std::vector<std::string> LogLabels(const std::vector<Log>& logs) {
  std::vector<std::string> labels;
  for (const auto& log : logs) labels.push_back(log.path);
  return labels;
}

/// Between-log test p below which a joint interval is widened.
inline constexpr double kWidenBelowP = 0.01;

/// For each test with p < kWidenBelowP: the joint estimate's std becomes at
/// least the random-effects std of the per-log mean (DerSimonian-Laird:
/// tau^2 = max(0, (Q - dof) / (S1 - S2 / S1)), S1 = sum 1/s_i^2,
/// S2 = sum 1/s_i^4; std = 1 / sqrt(sum 1/(s_i^2 + tau^2))) and its
/// interval +- t(m - 1) of it, with a note naming the parameter. The
/// covariance's row and column scale with it (correlations kept).
void WidenForDisagreement(FitResult& fit);

/// A warning for each test with p below 0.001.
std::vector<std::string> HeterogeneityWarnings(const std::vector<HeterogeneityTest>& tests);


/// A systematic error of the data that the residuals cannot show (e.g. a
/// log's timing, known only to within a logger step): with g = d(estimate)/
/// d(error) (one entry per estimate) and the error's std sigma, the
/// covariance gains sigma^2 g g'; each std, interval (its quantile kept) and
/// the correlations follow (docs/models.md#status-frames).
void AddSystematicCovariance(FitResult& fit, const std::vector<double>& gradient, double sigma);

}  // namespace driveid
