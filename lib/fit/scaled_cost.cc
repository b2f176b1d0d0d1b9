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
  // A Jacobian above kMemoJacobianBytes is not copied (memory before time:
  // models of such logs remember their last simulation themselves).
  memo_has_jacobian_ = jacobian != nullptr && n * p * sizeof(double) <= kMemoJacobianBytes;
  if (memo_has_jacobian_) memo_jacobian_.assign(jacobian, jacobian + n * p);
  memo_valid_ = true;
  return true;
}

ScaledBlockCost::ScaledBlockCost(BlockResidualModel& model, int block, std::vector<double> shared_scale,
                                 std::vector<double> local_scale)
    : model_(model), block_(block), shared_scale_(std::move(shared_scale)), local_scale_(std::move(local_scale)),
      shared_(shared_scale_.size()), local_(local_scale_.size()) {
  set_num_residuals(model.block_rows(block));
  if (!shared_scale_.empty()) mutable_parameter_block_sizes()->push_back(static_cast<int>(shared_scale_.size()));
  if (!local_scale_.empty()) mutable_parameter_block_sizes()->push_back(static_cast<int>(local_scale_.size()));
}

bool ScaledBlockCost::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  const std::size_t q = shared_scale_.size(), l = local_scale_.size(), p = q + l;
  const std::size_t n = static_cast<std::size_t>(num_residuals());
  const double* shared = q > 0 ? parameters[0] : nullptr;
  const double* local = l > 0 ? parameters[q > 0 ? 1 : 0] : nullptr;
  double* shared_jacobian = (jacobians != nullptr && q > 0) ? jacobians[0] : nullptr;
  double* local_jacobian = (jacobians != nullptr && l > 0) ? jacobians[q > 0 ? 1 : 0] : nullptr;
  const bool want_jacobian = shared_jacobian != nullptr || local_jacobian != nullptr;
  std::vector<double> point(shared, shared + q);
  point.insert(point.end(), local, local + l);
  if (!(memo_valid_ && memo_point_ == point && (!want_jacobian || memo_has_jacobian_))) {
    memo_valid_ = false;
    for (std::size_t j = 0; j < q; ++j) shared_[j] = shared[j] * shared_scale_[j];
    for (std::size_t j = 0; j < l; ++j) local_[j] = local[j] * local_scale_[j];
    memo_residuals_.resize(n);
    memo_jacobian_.resize(want_jacobian ? n * p : 0);
    if (!model_.EvaluateBlock(block_, shared_.data(), local_.data(), memo_residuals_.data(),
                              want_jacobian ? memo_jacobian_.data() : nullptr)) {
      return false;
    }
    for (std::size_t i = 0; i < memo_jacobian_.size(); ++i) {
      const std::size_t j = i % p;
      memo_jacobian_[i] *= j < q ? shared_scale_[j] : local_scale_[j - q];
    }
    memo_point_ = std::move(point);
    memo_has_jacobian_ = want_jacobian;
    memo_valid_ = true;
  }
  std::copy(memo_residuals_.begin(), memo_residuals_.end(), residuals);
  for (std::size_t i = 0; i < n; ++i) {
    if (shared_jacobian != nullptr) {
      std::copy_n(memo_jacobian_.data() + i * p, q, shared_jacobian + i * q);
    }
    if (local_jacobian != nullptr) {
      std::copy_n(memo_jacobian_.data() + i * p + q, l, local_jacobian + i * l);
    }
  }
  return true;
}

}  // namespace driveid
