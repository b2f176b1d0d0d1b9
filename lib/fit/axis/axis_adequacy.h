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

}  // namespace driveid
