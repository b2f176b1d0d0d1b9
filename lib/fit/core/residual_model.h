// What a fit is made of (fit/core/least_squares.h solves it): a model of
// residuals and their Jacobian, whole or in blocks; the free parameters; the
// measured channels; the solver's options.
#pragma once

#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/fit_options.h"

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

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

}  // namespace driveid
