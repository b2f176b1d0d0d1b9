// The cost Ceres minimises: a model on scaled parameters z = p / scale,
// with the Jacobian dr/dz = dr/dp scale. Scaling by typical magnitudes makes
// the trust region and the tolerances mean the same for an inertia of 1e-5
// and a friction of 5.
//
// The last evaluation is remembered: Ceres's bounded Levenberg-Marquardt
// asks for each new point three times (candidate with Jacobian, its cost,
// its Jacobian once accepted), and one simulation answers all three.
#pragma once

#include <vector>

#include <ceres/cost_function.h>

#include "fit/core/point_memo.h"
#include "fit/core/residual_model.h"

namespace driveid {

/// One block of a BlockResidualModel: parameter blocks (shared z, the
/// block's own z), either omitted when empty.
class ScaledBlockCost final : public ceres::CostFunction {
 public:
  /// `model` must outlive the cost; scales of the shared and own parameters.
  /// The memo keeps no Jacobian of a problem `large` counts as large.
  ScaledBlockCost(BlockResidualModel& model, int block, std::vector<double> shared_scale,
                  std::vector<double> local_scale, LargeProblemPolicy large = {});
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;
  /// Evaluations of the model so far (memoised repeats not counted).
  int model_evaluations() const { return evaluations_; }

 private:
  BlockResidualModel& model_;
  const int block_;
  const std::vector<double> shared_scale_, local_scale_;
  const LargeProblemPolicy large_;
  mutable std::vector<double> shared_, local_;
  // The last successful evaluation (fit/core/point_memo.h): the scaled point
  // (shared, then own), its residuals and, if computed and not large, its
  // scaled Jacobian (rows x (shared + own)).
  mutable PointMemo memo_;
  mutable std::vector<double> memo_residuals_, memo_jacobian_;
  mutable int evaluations_ = 0;
};

/// A ResidualModel seen as one block whose parameters are all shared.
class WholeModelBlock final : public BlockResidualModel {
 public:
  WholeModelBlock(ResidualModel& model, int parameter_count) : model_(model), parameters_(parameter_count) {}
  int shared_count() const override { return parameters_; }
  int block_count() const override { return 1; }
  int block_rows(int) const override { return model_.residual_count(); }
  int local_count(int) const override { return 0; }
  bool EvaluateBlock(int, const double* shared, const double*, double* residuals, double* jacobian) override {
    return model_.Evaluate(shared, residuals, jacobian);
  }
  std::string LastFailure() const override { return model_.LastFailure(); }

 private:
  ResidualModel& model_;
  const int parameters_;
};

/// Rows [begin, end) of a ResidualModel that evaluates row ranges
/// (ResidualModel::evaluates_rows; the model remembers its last point), on
/// one parameter block of scaled parameters.
class ScaledRowsCost final : public ceres::CostFunction {
 public:
  /// `model` must outlive the cost; `scale` has one entry per parameter.
  ScaledRowsCost(ResidualModel& model, int begin, int end, std::vector<double> scale);
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

 private:
  ResidualModel& model_;
  const int begin_, end_;
  const std::vector<double> scale_;
  mutable std::vector<double> physical_;
};

/// A ResidualModel's cost: one parameter block (ScaledBlockCost of the model
/// as one block).
class ScaledCost final : public ceres::CostFunction {
 public:
  /// `model` must outlive the cost; `scale` has one entry per parameter.
  ScaledCost(ResidualModel& model, std::vector<double> scale);
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    return cost_.Evaluate(parameters, residuals, jacobians);
  }
  int model_evaluations() const { return cost_.model_evaluations(); }

 private:
  WholeModelBlock whole_;
  ScaledBlockCost cost_;
};

}  // namespace driveid
