// The fit core: a model that cannot be evaluated is reported with its
// reason and the parameter values, so the user sees why (e.g. CVODES's
// message), not only that it failed.
#include "fit/core/least_squares.h"

#include <cmath>
#include <random>
#include <string>

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "core/errors.h"
#include "fit/core/fit_statistics.h"

using namespace driveid;

namespace {
class FailingModel final : public ResidualModel {
 public:
  int residual_count() const override { return 10; }
  bool Evaluate(const double*, double*, double*) override { return false; }
  std::string LastFailure() const override { return "integrator: CVode failed with code -4 (convergence test failures)"; }
};
}  // namespace

TEST_CASE("a model that cannot be evaluated: the reason and the parameter values reach the message") {
  FailingModel model;
  const std::vector<FitParameter> parameters = {{"d_g", 0.016, 0.0, 0.0}, {"tau_c", 5.0, 0.0, 0.0}};
  try {
    FitLeastSquares(model, parameters, {{"y", 0, 10, nullptr}}, {});
    FAIL("fitted a model that cannot be evaluated");
  } catch (const IdentificationError& e) {
    const std::string message = e.what();
    INFO(message);
    CHECK(message.find("d_g = 0.016") != std::string::npos);
    CHECK(message.find("tau_c = 5") != std::string::npos);
    CHECK(message.find("convergence test failures") != std::string::npos);
  }
}

TEST_CASE("Student t 97.5 % quantiles: exact values at small and large degrees of freedom") {
  // Reference values of the t distribution (two-sided 95 %).
  CHECK(StudentT975(1) == Approx(12.7062047362).epsilon(1e-9));
  CHECK(StudentT975(2) == Approx(4.30265272975).epsilon(1e-9));
  CHECK(StudentT975(10) == Approx(2.22813885196).epsilon(1e-9));
  CHECK(StudentT975(30) == Approx(2.04227245630).epsilon(1e-9));
  CHECK(StudentT975(100) == Approx(1.98397151852).epsilon(1e-9));
  CHECK(StudentT975(100000) == Approx(1.9599877).epsilon(1e-7));  // z + (z^3 + z) / (4 n)
  CHECK(std::isinf(StudentT975(0)));
}

namespace {

// y_bt = a (1 - exp(-b t)) + c_b + e_bt over B blocks of N samples: a, b
// shared, c_b each block's own; AR(1) errors (lag-1 0.8) so the robust
// covariance's long-run terms matter. Implements both interfaces.
class Saturation final : public ResidualModel, public BlockResidualModel {
 public:
  Saturation(int blocks, int samples) : blocks_(blocks), samples_(samples) {
    std::mt19937 engine(7);
    std::normal_distribution<double> noise(0.0, 0.05);
    for (int b = 0; b < blocks; ++b) {
      double e = 0.0;
      for (int k = 0; k < samples; ++k) {
        e = 0.8 * e + 0.6 * noise(engine);
        const double t = 0.01 * k;
        y_.push_back(2.0 * (1.0 - std::exp(-3.0 * t)) + 0.1 * b + e);
      }
    }
  }
  int residual_count() const override { return blocks_ * samples_; }
  bool Evaluate(const double* p, double* r, double* jacobian) override {
    const int width = 2 + blocks_;
    for (int b = 0; b < blocks_; ++b) {
      double* rows = jacobian ? jacobian + static_cast<std::ptrdiff_t>(b) * samples_ * width : nullptr;
      Block(b, p, p[2 + b], r + b * samples_, rows, width, 2 + b);
    }
    return true;
  }
  int shared_count() const override { return 2; }
  int block_count() const override { return blocks_; }
  int block_rows(int) const override { return samples_; }
  int local_count(int) const override { return 1; }
  bool EvaluateBlock(int b, const double* shared, const double* local, double* r, double* jacobian) override {
    Block(b, shared, local[0], r, jacobian, 3, 2);
    return true;
  }

 private:
  void Block(int b, const double* p, double c, double* r, double* jacobian, int width, int c_column) const {
    for (int k = 0; k < samples_; ++k) {
      const double t = 0.01 * k;
      const double decay = std::exp(-p[1] * t);
      r[k] = p[0] * (1.0 - decay) + c - y_[static_cast<std::size_t>(b * samples_ + k)];
      if (jacobian == nullptr) continue;
      double* row = jacobian + static_cast<std::ptrdiff_t>(k) * width;
      std::fill(row, row + width, 0.0);
      row[0] = 1.0 - decay;
      row[1] = p[0] * t * decay;
      row[c_column] = 1.0;
    }
  }
  int blocks_, samples_;
  std::vector<double> y_;
};

}  // namespace

TEST_CASE("parameters of their own per block: the Schur-complement fit equals the dense fit") {
  const int blocks = 6, samples = 150;
  Saturation model(blocks, samples);
  std::vector<FitParameter> parameters = {{"a", 1.0, 0.0, 0.0}, {"b", 1.5, 0.0, 0.0}};
  std::vector<FitChannel> channels;
  for (int b = 0; b < blocks; ++b) {
    parameters.push_back({"c_" + std::to_string(b + 1), 0.0, -INFINITY, 1.0});
    channels.push_back({"block " + std::to_string(b + 1), b * samples, samples, nullptr});
  }
  const FitResult dense = FitLeastSquares(model, parameters, channels, {});
  const FitResult block = FitBlockLeastSquares(model, parameters, channels, {});
  REQUIRE(dense.estimates.size() == block.estimates.size());
  for (std::size_t j = 0; j < dense.estimates.size(); ++j) {
    INFO(dense.estimates[j].name);
    CHECK(block.estimates[j].value == Approx(dense.estimates[j].value).epsilon(1e-5).margin(1e-6));
    CHECK(block.estimates[j].standard_error == Approx(dense.estimates[j].standard_error).epsilon(1e-4));
    CHECK(block.estimates[j].ci95_high - block.estimates[j].ci95_low ==
          Approx(dense.estimates[j].ci95_high - dense.estimates[j].ci95_low).epsilon(1e-4));
  }
  for (std::size_t i = 0; i < dense.correlation.size(); ++i) {
    CHECK(block.correlation[i] == Approx(dense.correlation[i]).margin(1e-5));
  }
  REQUIRE(block.singular_values.size() == dense.singular_values.size());
  for (std::size_t i = 0; i < dense.singular_values.size(); ++i) {
    CHECK(block.singular_values[i] == Approx(dense.singular_values[i]).epsilon(1e-6));
  }
  for (std::size_t c = 0; c < dense.channels.size(); ++c) {
    CHECK(block.channels[c].inflation == Approx(dense.channels[c].inflation).epsilon(1e-5));
    CHECK(block.channels[c].bandwidth == dense.channels[c].bandwidth);
  }
  // The correlated errors widen the interval: the robust std is larger than white noise's.
  CHECK(block.channels[0].inflation > 1.5);
  CHECK(std::abs(block.estimates[0].value - 2.0) < 4 * block.estimates[0].standard_error);
}

namespace {
// y = X p + AR(1) noise, X with correlated columns (an offset among them).
struct LinearProblem {
  RowMatrix x;
  Eigen::VectorXd y;
};
LinearProblem MakeLinearProblem(int n, const Eigen::Vector3d& truth, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  LinearProblem problem{RowMatrix(n, 3), Eigen::VectorXd(n)};
  double noise = 0.0;
  for (int k = 0; k < n; ++k) {
    const double t = 0.01 * k;
    problem.x.row(k) << std::sin(t), std::sin(t) + 0.3 * std::cos(3.0 * t), 1.0;
    noise = 0.8 * noise + 0.05 * normal(rng);
    problem.y(k) = problem.x.row(k).dot(truth) + noise;
  }
  return problem;
}

class LinearModel final : public ResidualModel {
 public:
  explicit LinearModel(const LinearProblem& problem) : problem_(problem) {}
  int residual_count() const override { return static_cast<int>(problem_.y.size()); }
  bool Evaluate(const double* parameters, double* residuals, double* jacobian) override {
    const Eigen::Map<const Eigen::Vector3d> p(parameters);
    Eigen::Map<Eigen::VectorXd>(residuals, problem_.y.size()) = problem_.x * p - problem_.y;
    if (jacobian != nullptr) Eigen::Map<RowMatrix>(jacobian, problem_.x.rows(), 3) = problem_.x;
    return true;
  }

 private:
  const LinearProblem& problem_;
};
}  // namespace

TEST_CASE("exact linear least squares: the QR solution, the bounded optimum, the iterative fit's statistics") {
  const int n = 2000;
  const std::vector<FitChannel> channels = {{"y", 0, n, nullptr}};
  SECTION("no bound active: Householder QR's solution, and the same standard errors as the iterative fit") {
    const LinearProblem problem = MakeLinearProblem(n, {2.0, 0.5, -0.3}, 3);
    const std::vector<FitParameter> parameters = {{"a", 1.0, 0.0, 0.0}, {"b", 1.0, 0.0, 0.0}, {"c", 0.1, -HUGE_VAL, 0.0}};
    JacobianBlock design;
    design.columns = {0, 1, 2};
    design.values = problem.x;
    const FitResult exact = FitLinearLeastSquares(std::move(design), problem.y, parameters, channels, {});
    const Eigen::Vector3d qr = problem.x.householderQr().solve(problem.y);
    LinearModel model(problem);
    const FitResult iterative = FitLeastSquares(model, parameters, channels, {});
    for (int j = 0; j < 3; ++j) {
      INFO("parameter " << j);
      CHECK(exact.estimates[static_cast<std::size_t>(j)].value == Approx(qr(j)).epsilon(1e-10));
      CHECK(iterative.estimates[static_cast<std::size_t>(j)].value ==
            Approx(qr(j)).margin(0.01 * exact.estimates[static_cast<std::size_t>(j)].standard_error));
      CHECK(exact.estimates[static_cast<std::size_t>(j)].standard_error ==
            Approx(iterative.estimates[static_cast<std::size_t>(j)].standard_error).epsilon(1e-4));
    }
    CHECK(exact.cost <= iterative.cost * (1.0 + 1e-12));
    CHECK(exact.channels.size() == 1);
  }
  SECTION("a bound active: the best of every choice of bound parameters that keeps the others feasible") {
    const LinearProblem problem = MakeLinearProblem(n, {2.0, -0.4, 0.3}, 4);  // b < 0 against its bound 0
    const std::vector<FitParameter> parameters = {{"a", 1.0, 0.0, 0.0}, {"b", 1.0, 0.0, 0.0}, {"c", 0.1, 0.0, 0.0}};
    JacobianBlock design;
    design.columns = {0, 1, 2};
    design.values = problem.x;
    const FitResult exact = FitLinearLeastSquares(std::move(design), problem.y, parameters, channels, {});
    // Brute force: every subset held at 0, the rest by QR, feasible ones compared by cost.
    double best_cost = HUGE_VAL;
    Eigen::Vector3d best = Eigen::Vector3d::Zero();
    for (int mask = 0; mask < 8; ++mask) {
      std::vector<int> open;
      for (int j = 0; j < 3; ++j) {
        if (!(mask & (1 << j))) open.push_back(j);
      }
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      if (!open.empty()) {
        RowMatrix sub(n, static_cast<Eigen::Index>(open.size()));
        for (std::size_t c = 0; c < open.size(); ++c) sub.col(static_cast<Eigen::Index>(c)) = problem.x.col(open[c]);
        const Eigen::VectorXd q = sub.householderQr().solve(problem.y);
        for (std::size_t c = 0; c < open.size(); ++c) p(open[c]) = q(static_cast<Eigen::Index>(c));
      }
      if ((p.array() < 0.0).any()) continue;
      const double cost = 0.5 * (problem.x * p - problem.y).squaredNorm();
      if (cost < best_cost) {
        best_cost = cost;
        best = p;
      }
    }
    REQUIRE(best(1) == 0.0);
    for (int j = 0; j < 3; ++j) {
      INFO("parameter " << j);
      CHECK(exact.estimates[static_cast<std::size_t>(j)].value == Approx(best(j)).epsilon(1e-9).margin(1e-12));
    }
    CHECK(exact.estimates[1].value == 0.0);
    CHECK(exact.termination.find("1 at a bound") != std::string::npos);
  }
}

TEST_CASE("long-run covariance: the FFT lag sum equals the Bartlett sum written out, lag by lag") {
  // Residuals with lag-1 about 0.45 (below the prewhitening threshold, so
  // the Bartlett window is applied to them directly) on 200 000 rows ask for
  // a bandwidth of about 70 lags: beyond the direct sum, through the FFT.
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  const Eigen::Index n = 200000;
  const Eigen::Index p = 3;
  Eigen::VectorXd e(n);
  double state = 0.0;
  for (Eigen::Index t = 0; t < n; ++t) e(t) = state = 0.45 * state + normal(rng);
  RowMatrix jacobian(n, p);
  for (Eigen::Index t = 0; t < n; ++t) {
    const double time = static_cast<double>(t) / 1000.0;
    jacobian.row(t) << std::sin(3.0 * time) + 0.1 * normal(rng), 1.0, time * std::exp(-0.1 * time);
  }
  const LongRunCovariance hac = CalcLongRunCovariance(jacobian, e);
  REQUIRE(hac.autocorrelation < 0.5);
  REQUIRE(hac.bandwidth > 32);
  // The definition: S = sum_{|l| <= L} (1 - |l| / (L + 1)) gamma_l sum_t J_{t+l}' J_t.
  const int lags = hac.bandwidth;
  Eigen::MatrixXd reference = (e.squaredNorm() / static_cast<double>(n)) * (jacobian.transpose() * jacobian);
  for (int l = 1; l <= lags; ++l) {
    double gamma = 0.0;
    for (Eigen::Index t = 0; t + l < n; ++t) gamma += e(t) * e(t + l);
    gamma /= static_cast<double>(n);
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(p, p);
    for (Eigen::Index t = 0; t + l < n; ++t) m += jacobian.row(t + l).transpose() * jacobian.row(t);
    reference += (1.0 - static_cast<double>(l) / (lags + 1.0)) * gamma * (m + m.transpose());
  }
  for (Eigen::Index i = 0; i < p; ++i) {
    for (Eigen::Index j = 0; j < p; ++j) {
      const double scale = std::sqrt(reference(i, i) * reference(j, j));
      INFO("entry " << i << ", " << j << ": " << hac.covariance(i, j) << " vs " << reference(i, j));
      CHECK(std::abs(hac.covariance(i, j) - reference(i, j)) <= 1e-9 * scale);
    }
  }
}
