#include "fit/core/scaled_cost.h"

#include <algorithm>
#include <cstring>

namespace driveid {

ScaledBlockCost::ScaledBlockCost(BlockResidualModel& model, int block, std::vector<double> shared_scale,
                                 std::vector<double> local_scale, LargeProblemPolicy large)
    : model_(model), block_(block), shared_scale_(std::move(shared_scale)), local_scale_(std::move(local_scale)),
      large_(large),
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
  if (memo_.Holds(shared, q, local, l) && (!want_jacobian || memo_.with_jacobian)) {
    std::copy(memo_residuals_.begin(), memo_residuals_.end(), residuals);
    for (std::size_t i = 0; i < n && want_jacobian; ++i) {
      if (shared_jacobian != nullptr) std::copy_n(memo_jacobian_.data() + i * p, q, shared_jacobian + i * q);
      if (local_jacobian != nullptr) std::copy_n(memo_jacobian_.data() + i * p + q, l, local_jacobian + i * l);
    }
    return true;
  }
  // A large Jacobian (LargeProblemPolicy) of shared parameters only goes
  // straight into Ceres's buffer and is not kept (memory before time: a
  // repeated point is evaluated again unless the model remembers it, as the
  // single-log step model does).
  const bool direct = want_jacobian && l == 0 && large_.IsLarge(n, p);
  memo_.Forget();
  for (std::size_t j = 0; j < q; ++j) shared_[j] = shared[j] * shared_scale_[j];
  for (std::size_t j = 0; j < l; ++j) local_[j] = local[j] * local_scale_[j];
  memo_jacobian_.resize(want_jacobian && !direct ? n * p : 0);
  memo_jacobian_.shrink_to_fit();
  double* jacobian = !want_jacobian ? nullptr : direct ? shared_jacobian : memo_jacobian_.data();
  ++evaluations_;
  if (!model_.EvaluateBlock(block_, shared_.data(), local_.data(), residuals, jacobian)) return false;
  for (std::size_t i = 0; jacobian != nullptr && i < n * p; ++i) {
    const std::size_t j = i % p;
    jacobian[i] *= j < q ? shared_scale_[j] : local_scale_[j - q];
  }
  for (std::size_t i = 0; i < n && want_jacobian && !direct; ++i) {
    if (shared_jacobian != nullptr) std::copy_n(memo_jacobian_.data() + i * p, q, shared_jacobian + i * q);
    if (local_jacobian != nullptr) std::copy_n(memo_jacobian_.data() + i * p + q, l, local_jacobian + i * l);
  }
  memo_residuals_.assign(residuals, residuals + n);
  memo_.Remember(shared, q, local, l);
  memo_.succeeded = true;
  memo_.with_jacobian = want_jacobian && !direct;
  return true;
}

ScaledRowsCost::ScaledRowsCost(ResidualModel& model, int begin, int end, std::vector<double> scale)
    : model_(model), begin_(begin), end_(end), scale_(std::move(scale)), physical_(scale_.size()) {
  set_num_residuals(end - begin);
  mutable_parameter_block_sizes()->push_back(static_cast<int>(scale_.size()));
}

bool ScaledRowsCost::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  const std::size_t p = scale_.size();
  for (std::size_t j = 0; j < p; ++j) physical_[j] = parameters[0][j] * scale_[j];
  double* jacobian = jacobians != nullptr ? jacobians[0] : nullptr;
  if (!model_.EvaluateRows(physical_.data(), begin_, end_, residuals, jacobian)) return false;
  const std::size_t values = static_cast<std::size_t>(end_ - begin_) * p;
  for (std::size_t i = 0; jacobian != nullptr && i < values; ++i) jacobian[i] *= scale_[i % p];
  return true;
}

ScaledCost::ScaledCost(ResidualModel& model, std::vector<double> scale)
    : whole_(model, static_cast<int>(scale.size())), cost_(whole_, 0, std::move(scale), {}) {
  set_num_residuals(model.residual_count());
  mutable_parameter_block_sizes()->push_back(static_cast<int>(cost_.parameter_block_sizes().front()));
}

}  // namespace driveid
