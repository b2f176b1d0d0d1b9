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

}  // namespace driveid
