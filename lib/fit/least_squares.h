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

namespace driveid {

/// A model whose residuals r(p) = y_model(p) - y_measured and Jacobian
/// dr/dp = dy_model/dp can be evaluated together (one simulation per call).
class ResidualModel {
 public:
  virtual ~ResidualModel() = default;
  virtual int residual_count() const = 0;
  /// Fills `residuals` (length N) and, if `jacobian` is non-null, the
  /// row-major N x P Jacobian in physical units. Returns false if the model
  /// cannot be evaluated at `parameters` (the solver then backs off).
  virtual bool Evaluate(const double* parameters, double* residuals, double* jacobian) = 0;
  /// Why the last Evaluate returned false (e.g. the integrator's reason), or "".
  virtual std::string LastFailure() const { return {}; }
  /// Whether EvaluateRows is available: models that remember their last
  /// point (a simulation) answer row ranges without evaluating again, so a
  /// large problem goes to the solver in chunks of rows (no scratch Jacobian
  /// of all rows besides the solver's own).
  virtual bool evaluates_rows() const { return false; }
  /// Rows [begin, end) only: `residuals` and the Jacobian's rows start at row
  /// `begin`. Only called if evaluates_rows().
  virtual bool EvaluateRows(const double* /*parameters*/, int /*begin*/, int /*end*/, double* /*residuals*/,
                            double* /*jacobian*/) {
    return false;
  }
  /// Frees what the model holds between evaluations (called when the fit is done).
  virtual void Release() {}
};

/// Residuals in blocks (e.g. one per log) whose rows depend on the shared
/// parameters and on parameters of their own only (a log's offset). Fitted
/// with a Schur-complement solver that eliminates the blocks' own
/// parameters, so that time and memory grow linearly with the blocks.
class BlockResidualModel {
 public:
  virtual ~BlockResidualModel() = default;
  virtual int shared_count() const = 0;
  virtual int block_count() const = 0;
  virtual int block_rows(int block) const = 0;
  virtual int local_count(int block) const = 0;
  /// Fills the block's residuals (block_rows) and, if `jacobian` is
  /// non-null, its row-major rows x (shared_count + local_count) Jacobian in
  /// physical units. Returns false if the model cannot be evaluated there.
  virtual bool EvaluateBlock(int block, const double* shared, const double* local, double* residuals,
                             double* jacobian) = 0;
  virtual std::string LastFailure() const { return {}; }
};

/// A free parameter: name (parameter-file key), start value and lower bound.
struct FitParameter {
  std::string name;
  double initial = 0.0;
  double lower_bound = -std::numeric_limits<double>::infinity();  ///< 0 for physical parameters
  double scale = 0.0;  ///< typical magnitude; 0 = |initial| (or 1 if initial is 0)
};

/// A measured channel occupying residuals [begin, begin + count).
struct FitChannel {
  std::string name;
  int begin = 0;
  int count = 0;
  const double* measured = nullptr;  ///< count values, for fit percent
};

/// Progress of one solver iteration (for -v).
struct FitIteration {
  int iteration;
  double cost;
  double gradient_norm;
  double step_norm;
};

struct FitOptions {
  int max_iterations = 100;
  /// Smallest singular value of the column-normalised Jacobian below which
  /// the parameters count as not identifiable (collinearity index 1/s > 1000).
  double identifiability_threshold = 1e-3;
  /// Optional advice for a non-identifiable set, given the parameters involved.
  std::function<std::string(const std::vector<std::string>&)> advice;
  std::function<void(const FitIteration&)> progress;
};

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

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct JacobianBlock;  // fit/fit_statistics.h

/// A linear model r = X p - y (X: `design`, one block with every column)
/// solved exactly: the normal equations on column-normalised X with an
/// active set for the lower bounds, no solver iterations and no copy of X,
/// which becomes the statistics' Jacobian. For designs too large to hold
/// twice (LinearRegression::FitAndRelease); same statistics and refusals as
/// FitLeastSquares.
FitResult FitLinearLeastSquares(JacobianBlock design, const Eigen::VectorXd& y,
                                const std::vector<FitParameter>& parameters, const std::vector<FitChannel>& channels,
                                const FitOptions& options);

/// Long-run covariance of the scores J_t' r_t of one channel (rows in time
/// order) for stationary errors, AR(1)-prewhitened: with rho the residuals'
/// lag-1 autocorrelation, u_t = r_t - rho r_{t-1} and G_s = sum_{t>=s}
/// rho^(t-s) J_t (exactly sum_t J_t' r_t = sum_s G_s' u_s), the Bartlett
/// estimate on (G, u) with Andrews' AR(1) plug-in bandwidth from u's lag-1
/// autocorrelation (least_squares.cc).
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

/// Root mean square deviation of `values` from their mean (0 for none): the
/// scale by which fits weight a channel against another of other units.
double CalcRmsDeviation(const std::vector<double>& values);

/// Two-sided 97.5 % quantile of Student's t with `dof` degrees of freedom.
double StudentT975(int dof);

}  // namespace driveid
