// The axis fit's adequacy (docs/models.md#adequacy): the terms its
// residuals ask for (fit/core/omitted_terms.h), each with what to do, a
// remedy named only where its fit works.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "core/fit_result.h"
#include "fit/core/linear_regression.h"

namespace driveid {

/// The fit's warnings and those of the omitted-term tests: a term to free is
/// named only where the fit with it free runs, is well conditioned and
/// determines it; on a linear axis gravity is a constant force, the offset,
/// and has no cos q / sin q test.
std::vector<std::string> CheckAxisAdequacy(const LinearRegression& regression, const FitResult& fit,
                                           const std::vector<std::string>& free,
                                           const std::map<std::string, double>& values, bool linear);

/// An inertia the data do not determine is refused, not bounded, where the
/// rate varies within the logs by less than this fraction of its RMS
/// (AxisFitOutput::rate_variation): the logs hold no change of speed for it
/// to act in, the decimated q'' is the encoder's noise, and that noise in
/// the regressor pulls the estimate towards 0, so a bound from it would be
/// confidently wrong (constant-rate logs: 6e-6 +- 3e-4 for a true 0.05).
inline constexpr double kAxisMinRateVariation = 0.05;

/// The axis parameters physics bounds at 0 (inertia, friction), of all terms.
std::vector<std::string> AxisNonnegativeKeys();

/// The axis fits' determination rule (adequacy.h BoundOrRefuse) on their
/// final covariance, after every widening: a non-negative parameter the data
/// bound is reported with its interval cut at 0 and a warning; one they say
/// nothing about is refused by name (exit 4), an inertia so where
/// `rate_variation` (AxisFitOutput::rate_variation; negative: not measured,
/// as in output error, which does not differentiate) is below
/// kAxisMinRateVariation.
void DecideAxisDetermined(FitResult& fit, double max_relative_std, double rate_variation);

}  // namespace driveid
