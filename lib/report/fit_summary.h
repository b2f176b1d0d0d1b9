// Text renderings of a fit's result for people (table) and programs (JSON).
// Formatting only: the caller decides where the text goes.
#pragma once

#include <string>

#include "core/fit_result.h"
#include "report/json.h"

namespace driveid {

/// "12.34 %"; for NaN "n/a (nearly constant: std 3.1 % of its RMS)" given
/// the channel's `variation` (ChannelStatistics), else "n/a (constant)".
std::string FitPercentText(double fit_percent, double variation = 0.0);

/// Human-readable table: estimates with std, 95 % interval and relative
/// error, per-channel RMSE and fit %, correlations, solver status, per-log
/// estimates and the adequacy warnings.
std::string FormatFitTable(const FitResult& fit, const FitProvenance& provenance);

/// Processing-sensitivity and per-log estimates, heterogeneity statistics ("" if none).
std::string FormatPerLogTable(const FitResult& fit);

/// Validation of logs predicted from a parameter file: per log samples,
/// RMSE, fit % and residual lag-1 autocorrelation (docs/models.md#validation).
std::string FormatValidationTable(const std::vector<ChannelStatistics>& logs);
Json ValidationJson(const std::vector<ChannelStatistics>& logs);

/// The same content as one JSON object (deterministic key order).
Json FitJson(const FitResult& fit, const FitProvenance& provenance);

}  // namespace driveid
