// Adequacy of a linear inverse-dynamics fit (docs/models.md#adequacy): does
// a term left out of the model explain the residuals? The candidate's
// columns Z are projected off the fitted columns X (Frisch-Waugh:
// Z~ = Z - X (X'X)^-1 X'Z), the residuals e are regressed on Z~, and the
// coefficients g are tested with the same autocorrelation-robust covariance
// as the fit (per channel, Bartlett, Andrews bandwidth):
//   W = g' Cov(g)^-1 g  ~  chi^2(k) under "the term is absent",
//   share = e'Z~ g / e'e, the part of the residual sum of squares it explains.
// A term is reported as missing when W exceeds the chi^2 0.999 quantile and
// the share is at least `min_share` (an effect large enough to matter, not
// just detectable in a long log).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "fit/core/linear_regression.h"

namespace driveid {

struct OmittedTermTest {
  std::string term;      ///< candidate's name
  double share = 0.0;    ///< fraction of the residual sum of squares it explains
  double wald = 0.0;     ///< robust Wald statistic
  int dof = 0;           ///< columns tested (after dropping ones the fit already spans)
  double critical = 0.0; ///< chi^2(dof) 0.999 quantile
  bool missing = false;  ///< wald > critical and share >= min_share
  /// The residual's coefficient on each candidate column (0 for one the fit already spans).
  std::vector<double> coefficients;
};

/// Tests candidate `columns` (names of regression columns that the fit held
/// at 0 or a fixed value) against the residuals of the fit whose free
/// columns are `free` and whose column values are `values` (all columns).
OmittedTermTest TestOmittedTerm(const LinearRegression& regression, const std::vector<std::string>& free,
                                const std::map<std::string, double>& values, const std::string& term,
                                const std::vector<std::string>& columns, double min_share = 0.1);

}  // namespace driveid
