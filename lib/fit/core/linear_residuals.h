// A linear model y = X p for the fit core: residuals X p - y, Jacobian X.
// Used by the inverse-dynamics fits (C-drive, axis, robot). X is read from
// the design's rows where they lie (some of their columns), not copied, and
// rows can be evaluated in ranges (the solver takes a large X in chunks).
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "fit/core/least_squares.h"

namespace driveid {

class LinearResiduals final : public ResidualModel {
 public:
  /// X = columns `free` of `design` (row-major, `width` values per row,
  /// y.size() rows; must outlive this).
  LinearResiduals(const double* design, std::size_t width, std::vector<std::size_t> free, Eigen::VectorXd y)
      : design_(design), width_(width), free_(std::move(free)), y_(std::move(y)) {}
  int residual_count() const override { return static_cast<int>(y_.size()); }
  bool Evaluate(const double* parameters, double* residuals, double* jacobian) override {
    return EvaluateRows(parameters, 0, residual_count(), residuals, jacobian);
  }
  bool evaluates_rows() const override { return true; }
  bool EvaluateRows(const double* parameters, int begin, int end, double* residuals, double* jacobian) override {
    const std::size_t p = free_.size();
    for (int row = begin; row < end; ++row) {
      const double* x = design_ + static_cast<std::size_t>(row) * width_;
      const std::size_t i = static_cast<std::size_t>(row - begin);
      double sum = 0.0;
      for (std::size_t c = 0; c < p; ++c) {
        sum += x[free_[c]] * parameters[c];
        if (jacobian != nullptr) jacobian[i * p + c] = x[free_[c]];
      }
      residuals[i] = sum - y_(row);
    }
    return true;
  }

 private:
  const double* design_;
  const std::size_t width_;
  const std::vector<std::size_t> free_;
  const Eigen::VectorXd y_;
};

}  // namespace driveid
