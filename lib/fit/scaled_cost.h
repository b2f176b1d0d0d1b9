// The cost Ceres minimises: a ResidualModel on scaled parameters
// z = p / scale, one parameter block, with the Jacobian dr/dz = dr/dp scale.
// Scaling by typical magnitudes makes the trust region and the tolerances
// mean the same for an inertia of 1e-5 and a friction of 5.
//
// The last evaluation is remembered: Ceres's bounded Levenberg-Marquardt
// asks for each new point three times (candidate with Jacobian, its cost,
// its Jacobian once accepted), and one simulation answers all three.
#pragma once

#include <vector>

#include <ceres/cost_function.h>

#include "fit/least_squares.h"

namespace driveid {

/// Largest Jacobian the memo copies [bytes].
inline constexpr std::size_t kMemoJacobianBytes = std::size_t{16} << 20;

class ScaledCost final : public ceres::CostFunction {
 public:
  /// `model` must outlive the cost; `scale` has one entry per parameter.
  ScaledCost(ResidualModel& model, std::vector<double> scale);
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;
  /// Evaluations of the model so far (memoised repeats not counted).
  int model_evaluations() const { return evaluations_; }

 private:
  ResidualModel& model_;
  const std::vector<double> scale_;
  mutable std::vector<double> physical_;
  // Memo of the last successful evaluation: the scaled point (compared bit
  // for bit), its residuals and, if computed, its scaled Jacobian.
  mutable std::vector<double> memo_point_;
  mutable std::vector<double> memo_residuals_;
  mutable std::vector<double> memo_jacobian_;
  mutable bool memo_valid_ = false;
  mutable bool memo_has_jacobian_ = false;
  mutable int evaluations_ = 0;
};

/// One block of a BlockResidualModel on scaled parameters: parameter blocks
/// (shared z, the block's own z), the latter omitted when it has none, with
/// the same memo of the last point.
class ScaledBlockCost final : public ceres::CostFunction {
 public:
  /// `model` must outlive the cost; scales of the shared and own parameters.
  ScaledBlockCost(BlockResidualModel& model, int block, std::vector<double> shared_scale,
                  std::vector<double> local_scale);
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

 private:
  BlockResidualModel& model_;
  const int block_;
  const std::vector<double> shared_scale_, local_scale_;
  mutable std::vector<double> shared_, local_;
  mutable std::vector<double> memo_point_, memo_residuals_, memo_jacobian_;
  mutable bool memo_valid_ = false;
  mutable bool memo_has_jacobian_ = false;
};

}  // namespace driveid
