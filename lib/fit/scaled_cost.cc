#include "fit/scaled_cost.h"

#include <algorithm>
#include <cstring>

namespace driveid {

ScaledCost::ScaledCost(ResidualModel& model, std::vector<double> scale)
    : model_(model), scale_(std::move(scale)), physical_(scale_.size()) {
  set_num_residuals(model.residual_count());
  mutable_parameter_block_sizes()->push_back(static_cast<int>(scale_.size()));
}

bool ScaledCost::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  const std::size_t p = scale_.size();
  const std::size_t n = static_cast<std::size_t>(num_residuals());
  double* jacobian = (jacobians != nullptr) ? jacobians[0] : nullptr;
  // Bitwise comparison: a point that differs in the last bit is another point.
  const bool same_point = memo_valid_ && std::memcmp(memo_point_.data(), parameters[0], p * sizeof(double)) == 0;
  if (same_point && (jacobian == nullptr || memo_has_jacobian_)) {
    std::copy(memo_residuals_.begin(), memo_residuals_.end(), residuals);
    if (jacobian != nullptr) std::copy(memo_jacobian_.begin(), memo_jacobian_.end(), jacobian);
    return true;
  }
  memo_valid_ = false;
  for (std::size_t j = 0; j < p; ++j) physical_[j] = parameters[0][j] * scale_[j];
  ++evaluations_;
  if (!model_.Evaluate(physical_.data(), residuals, jacobian)) return false;
  if (jacobian != nullptr) {
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = 0; j < p; ++j) jacobian[i * p + j] *= scale_[j];
    }
  }
  memo_point_.assign(parameters[0], parameters[0] + p);
  memo_residuals_.assign(residuals, residuals + n);
  memo_has_jacobian_ = jacobian != nullptr;
  if (memo_has_jacobian_) memo_jacobian_.assign(jacobian, jacobian + n * p);
  memo_valid_ = true;
  return true;
}

}  // namespace driveid
