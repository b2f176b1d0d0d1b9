// The cost Ceres minimises: a ResidualModel on scaled parameters
// z = p / scale, one parameter block, with the Jacobian dr/dz = dr/dp scale.
// Scaling by typical magnitudes makes the trust region and the tolerances
// mean the same for an inertia of 1e-5 and a friction of 5.
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

 private:
  ResidualModel& model_;
  const std::vector<double> scale_;
  mutable std::vector<double> physical_;
};

}  // namespace driveid
