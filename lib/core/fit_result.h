// Plain result types of a fit (no solver headers): what every fitting
// command reports (docs/models.md#identification) and writes into the parameter file.
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace driveid {

/// One estimated parameter, in its physical unit.
struct ParameterEstimate {
  std::string name;
  double value = 0.0;
  double standard_error = 0.0;  ///< from the Jacobian at the optimum
  double ci95_low = 0.0;        ///< 95 % confidence interval (Student t)
  double ci95_high = 0.0;
  std::string unit{};           ///< as the command knows it ("": not stated)
};

/// The suffix of an inverse-dynamics fit's torque channel, named after its
/// log ("log.csv:tau"; fit/axis/axis_rows.h, the design's noise).
inline constexpr char kTorqueChannelSuffix[] = ":tau";

/// Goodness of fit of one measured channel (e.g. tau_link of one log).
struct ChannelStatistics {
  std::string name;
  int samples = 0;
  double rmse = 0.0;         ///< root mean square residual, channel unit
  /// NRMSE fit, 100 (1 - |y - yhat| / |y - mean(y)|); NaN when the measured
  /// channel does not vary (its spread is below 1e-9 of its magnitude) or
  /// hardly varies (`variation` below kNearlyConstant): a fit % against a
  /// near-constant means nothing (shown as "n/a", null in JSON and files).
  double fit_percent = 0.0;
  /// std(y) / RMS(y) of the measured channel (NaN: none measured).
  double variation = std::numeric_limits<double>::quiet_NaN();
  /// 100 |y - yhat| / |y| (NaN: none measured, or all zero): the error
  /// relative to the signal itself, as robot identification reports it.
  double relative_error_percent = std::numeric_limits<double>::quiet_NaN();
  double autocorrelation = 0.0;  ///< lag-1 autocorrelation of the residuals
  int bandwidth = 0;             ///< Newey-West lags used (Andrews' AR(1) rule; 0: none)
  double inflation = 1.0;        ///< std with / without the correlation of residuals (trace ratio, sqrt)
};

/// Estimates of a variant of the fit (one log alone, another cutoff) or why
/// that fit failed; `label` says which.
struct EstimateSet {
  std::string label;
  std::vector<ParameterEstimate> estimates;
  std::string failure;
  double cutoff = 0.0;  ///< the filter cutoff [Hz] of a processing-sensitivity fit (0: other sets)
};

/// Cochran's Q for one parameter over the logs that estimated it:
/// Q = sum_i (b_i - b_w)^2 / s_i^2 with b_w the inverse-variance mean,
/// chi^2(m - 1) when the logs agree; I^2 = max(0, (Q - dof) / Q).
struct HeterogeneityTest {
  std::string parameter;
  double q = 0.0;
  int dof = 0;
  double p_value = 1.0;
  double i_squared = 0.0;
};

struct FitResult {
  std::vector<ParameterEstimate> estimates;
  std::vector<double> covariance;        ///< row-major P x P, physical units
  std::vector<double> correlation;       ///< row-major P x P
  std::vector<ChannelStatistics> channels;
  std::vector<double> singular_values;   ///< of the column-normalised Jacobian, descending
  int iterations = 0;
  bool converged = false;
  double cost = 0.0;                     ///< 1/2 sum of squared residuals
  std::string termination;               ///< solver's reason for stopping
  /// Adequacy warnings (docs/models.md#adequacy): the fit ran, but the data
  /// say the model misses something; `--strict` turns them into exit 4.
  std::vector<std::string> warnings;
  /// What the reader should know that is no warning (e.g. a parameter
  /// reported at its bound with a one-sided limit).
  std::vector<std::string> notes;
  std::vector<EstimateSet> per_log;             ///< several logs: each fitted alone
  std::vector<EstimateSet> sensitivity;         ///< the same fit with other processing (cutoffs)
  std::vector<HeterogeneityTest> heterogeneity;  ///< per parameter, over per_log
  std::vector<ChannelStatistics> validation;     ///< held-out logs (--validate) predicted by the fit
};

/// Above this many parameters (e.g. a fit of many logs with an offset
/// each) reports show the strongest correlations instead of the matrix,
/// and the text summary condenses its per-channel lines.
inline constexpr std::size_t kFullCorrelationParameters = 40;
inline constexpr std::size_t kListedChannels = 20;

/// A pair of estimates and their correlation.
struct CorrelationPair {
  std::size_t first = 0, second = 0;  ///< indices into FitResult::estimates, first > second
  double correlation = 0.0;
};

/// The `count` pairs of largest |correlation| (ties: the earlier pair; NaN
/// weakest), strongest first.
inline std::vector<CorrelationPair> StrongestCorrelations(const FitResult& fit, std::size_t count) {
  const std::size_t p = fit.estimates.size();
  std::vector<CorrelationPair> pairs;
  for (std::size_t i = 0; i < p; ++i) {
    for (std::size_t j = 0; j < i; ++j) pairs.push_back({i, j, fit.correlation[i * p + j]});
  }
  // |r|, and a NaN (an estimate without a std) weakest of all: a NaN in the
  // comparison would break the ordering and list it among the strongest.
  const auto strength = [](double r) { return r != r ? -1.0 : r < 0 ? -r : r; };
  const auto stronger = [&](const CorrelationPair& a, const CorrelationPair& b) {
    const double x = strength(a.correlation), y = strength(b.correlation);
    return x > y || (x == y && (a.first < b.first || (a.first == b.first && a.second < b.second)));
  };
  const std::size_t kept = count < pairs.size() ? count : pairs.size();
  std::partial_sort(pairs.begin(), pairs.begin() + static_cast<std::ptrdiff_t>(kept), pairs.end(), stronger);
  pairs.resize(kept);
  return pairs;
}

/// A quantity derived from the estimates (e.g. the C-drive's a and b), with
/// its standard error propagated through the covariance.
struct DerivedQuantity {
  std::string name;
  double value = 0.0;
  double standard_error = 0.0;
  std::string unit;
};

/// One input file of a fit, for provenance.
struct DataFileRecord {
  std::string file;
  std::string sha256;
  int samples = 0;
  std::string segment;             ///< part of the file ("slow-forward"), "" for all of it
  std::vector<std::string> notes;  ///< expressions, crops, joins (with their sha256), reader notes
};

/// What produced a fit (goes into the parameter file's `fit` section).
struct FitProvenance {
  std::string command;  ///< the exact command line
  std::string version;  ///< tool version
  std::string model;    ///< model variant, e.g. "reduced"
  std::vector<DataFileRecord> data;
};

}  // namespace driveid
