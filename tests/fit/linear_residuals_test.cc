// The linear model y = X p of the inverse-dynamics fits
// (fit/core/linear_residuals.h): residuals and Jacobian read from chosen columns
// of a row-major design, the same in row ranges as whole, and the fit core
// on it landing on the least-squares solution of the normal equations.
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "fit/core/least_squares.h"
#include "fit/core/linear_residuals.h"

namespace driveid {
namespace {

TEST_CASE("residuals X p - y and Jacobian X from the chosen columns, whole or in row ranges; the fit's optimum") {
  const int rows = 200;
  const std::size_t width = 5;
  const std::vector<std::size_t> free{4, 0, 2};
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> design(rows * width);
  for (auto& v : design) v = normal(rng);
  Eigen::MatrixXd x(rows, 3);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < 3; ++c) x(r, c) = design[static_cast<std::size_t>(r) * width + free[static_cast<std::size_t>(c)]];
  }
  const Eigen::Vector3d truth(1.5, -0.5, 2.0);
  Eigen::VectorXd y = x * truth;
  for (int r = 0; r < rows; ++r) y(r) += 0.1 * normal(rng);
  LinearResiduals model(design.data(), width, free, y);
  REQUIRE(model.residual_count() == rows);
  REQUIRE(model.evaluates_rows());

  const Eigen::Vector3d p(0.3, 0.7, -1.1);
  Eigen::VectorXd residuals(rows);
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> jacobian(rows, 3);
  REQUIRE(model.Evaluate(p.data(), residuals.data(), jacobian.data()));
  CHECK((residuals - (x * p - y)).cwiseAbs().maxCoeff() < 1e-12);
  CHECK(jacobian == x);
  // Rows 37 .. 120 alone: the same rows.
  Eigen::VectorXd part(83);
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> part_jacobian(83, 3);
  REQUIRE(model.EvaluateRows(p.data(), 37, 120, part.data(), part_jacobian.data()));
  CHECK(part == residuals.segment(37, 83));
  CHECK(part_jacobian == jacobian.middleRows(37, 83));
  REQUIRE(model.Evaluate(p.data(), residuals.data(), nullptr));  // without the Jacobian

  // The fit core lands on (X'X)^-1 X'y, within the solver's tolerances
  // (cost change 1e-7: here about 0.002 standard errors), and its standard
  // errors are s sqrt(diag (X'X)^-1), s^2 the residual variance on n - 3.
  const Eigen::Vector3d normal_solution = (x.transpose() * x).ldlt().solve(x.transpose() * y);
  const std::vector<FitParameter> parameters{{"a", 0.0, -1e9, 1.0}, {"b", 0.0, -1e9, 1.0}, {"c", 0.0, -1e9, 1.0}};
  const FitResult fit = FitLeastSquares(model, parameters, {{"y", 0, rows, nullptr}}, {});
  REQUIRE(fit.estimates.size() == 3);
  const double s2 = (x * normal_solution - y).squaredNorm() / (rows - 3);
  const Eigen::Matrix3d inverse = (x.transpose() * x).inverse();
  for (int j = 0; j < 3; ++j) {
    const ParameterEstimate& e = fit.estimates[static_cast<std::size_t>(j)];
    INFO(e.name);
    CHECK(e.standard_error == Approx(std::sqrt(s2 * inverse(j, j))).epsilon(0.02));
    CHECK(std::abs(e.value - normal_solution(j)) < 0.01 * e.standard_error);
  }
}

}  // namespace
}  // namespace driveid
