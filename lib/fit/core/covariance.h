// Covariance of a fit's scores under serially correlated errors
// (docs/models.md#identification): the long-run (HAC) covariance that the
// robust standard errors use (fit/core/fit_statistics.cc).
#pragma once

#include <Eigen/Core>

#include "fit/core/residual_model.h"

namespace driveid {

/// Long-run covariance of the scores J_t' r_t of one channel (rows in time
/// order) for stationary errors, AR(1)-prewhitened: with rho the residuals'
/// lag-1 autocorrelation, u_t = r_t - rho r_{t-1} and G_s = sum_{t>=s}
/// rho^(t-s) J_t (exactly sum_t J_t' r_t = sum_s G_s' u_s), the Bartlett
/// estimate on (G, u) with Andrews' AR(1) plug-in bandwidth from u's lag-1
/// autocorrelation (covariance.cc).
struct LongRunCovariance {
  Eigen::MatrixXd covariance;  ///< sum_{|l|<=L} w_l gamma_u(l) sum_t G_t' G_{t-l}
  double autocorrelation = 0.0;  ///< lag-1 of the residuals r
  int bandwidth = 0;             ///< L, lags of u used
};
LongRunCovariance CalcLongRunCovariance(const Eigen::Ref<const RowMatrix>& jacobian,
                                        const Eigen::Ref<const Eigen::VectorXd>& residuals);
/// The same, overwriting `jacobian` with G (no copy of it).
LongRunCovariance CalcLongRunCovarianceInPlace(Eigen::Ref<RowMatrix> jacobian,
                                               const Eigen::Ref<const Eigen::VectorXd>& residuals);

}  // namespace driveid
