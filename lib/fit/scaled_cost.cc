#include "fit/scaled_cost.h"

namespace driveid {

ScaledCost::ScaledCost(ResidualModel& model, std::vector<double> scale)
    : model_(model), scale_(std::move(scale)), physical_(scale_.size()) {
  set_num_residuals(model.residual_count());
  mutable_parameter_block_sizes()->push_back(static_cast<int>(scale_.size()));
}

bool ScaledCost::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  const std::size_t p = scale_.size();
  for (std::size_t j = 0; j < p; ++j) physical_[j] = parameters[0][j] * scale_[j];
  double* jacobian = (jacobians != nullptr) ? jacobians[0] : nullptr;
  if (!model_.Evaluate(physical_.data(), residuals, jacobian)) return false;
  if (jacobian != nullptr) {
    const std::size_t n = static_cast<std::size_t>(num_residuals());
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = 0; j < p; ++j) jacobian[i * p + j] *= scale_[j];
    }
  }
  return true;
}

}  // namespace driveid
