// A linear model y = X p for the fit core: residuals X p - y, Jacobian X.
// Used by the inverse-dynamics fits (C-drive, axis, robot).
#pragma once

#include <Eigen/Dense>

#include "fit/least_squares.h"

namespace driveid {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

class LinearResiduals final : public ResidualModel {
 public:
  LinearResiduals(RowMatrix regressor, Eigen::VectorXd measured)
      : regressor_(std::move(regressor)), measured_(std::move(measured)) {}
  int residual_count() const override { return static_cast<int>(measured_.size()); }
  bool Evaluate(const double* parameters, double* residuals, double* jacobian) override {
    const Eigen::Map<const Eigen::VectorXd> p(parameters, regressor_.cols());
    Eigen::Map<Eigen::VectorXd>(residuals, measured_.size()) = regressor_ * p - measured_;
    if (jacobian != nullptr) Eigen::Map<RowMatrix>(jacobian, regressor_.rows(), regressor_.cols()) = regressor_;
    return true;
  }

 private:
  const RowMatrix regressor_;
  const Eigen::VectorXd measured_;
};

}  // namespace driveid
