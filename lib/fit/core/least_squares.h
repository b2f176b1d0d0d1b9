// Fit core shared by all models: bounded nonlinear least squares (Ceres,
// Levenberg-Marquardt) on parameters scaled by their starting values, an
// identifiability check on the column-normalised Jacobian before and after
// the solve, and statistics (docs/models.md#identification).
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/fit_result.h"
#include "fit/core/covariance.h"
#include "fit/core/fit_statistics.h"
#include "fit/core/residual_model.h"

namespace driveid {

/// Solves the problem and returns estimates with statistics. Throws
/// IdentificationError when the parameters are not identifiable (naming
/// them), when the solver fails or does not converge.
FitResult FitLeastSquares(ResidualModel& model, const std::vector<FitParameter>& parameters,
                          const std::vector<FitChannel>& channels, const FitOptions& options);

/// The same for a model in blocks: `parameters` lists the shared ones, then
/// each block's own in block order; rows are the blocks' rows in order.
FitResult FitBlockLeastSquares(BlockResidualModel& model, const std::vector<FitParameter>& parameters,
                               const std::vector<FitChannel>& channels, const FitOptions& options);

/// Removes the estimates whose `keep` is false (nuisance parameters such as
/// a simulation's initial state) with their rows and columns of the
/// covariance and correlation; the rest of the fit stays as solved.
void DropParameters(FitResult& fit, const std::vector<bool>& keep);

/// A linear model r = X p - y (X: `design`, one block with every column)
/// solved exactly: the normal equations on column-normalised X with an
/// active set for the lower bounds, no solver iterations and no copy of X,
/// which becomes the statistics' Jacobian. For designs too large to hold
/// twice (LinearRegression::FitAndRelease); same statistics and refusals as
/// FitLeastSquares.
FitResult FitLinearLeastSquares(JacobianBlock design, const Eigen::VectorXd& y,
                                const std::vector<FitParameter>& parameters, const std::vector<FitChannel>& channels,
                                const FitOptions& options);

}  // namespace driveid
