#include "fit/consistent_parameters.h"

#include <cmath>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <ceres/ceres.h>

#include "models/pseudo_inertia.h"
#include "models/serial_dynamics.h"

namespace driveid {
namespace {

constexpr int kBodyBlock = 10, kDriveBlock = 4;

// A trial step that overflows exp() is refused (false: Ceres shrinks the
// step) instead of handing Ceres non-finite values, which it would report.
double Real(double x) { return x; }
template <class Jet>
double Real(const Jet& x) {
  return x.a;
}
template <class T>
bool AllFinite(const T* values, int count) {
  for (int i = 0; i < count; ++i) {
    if (!std::isfinite(Real(values[i]))) return false;
  }
  return true;
}

// r = L^-1 (R theta - beta_hat), C = L L^T: the data's cost about the fit.
struct DataCost {
  const Eigen::MatrixXd* regroup;  // r x 14 n
  const Eigen::MatrixXd* whiten;   // L^-1, r x r
  const Eigen::VectorXd* estimate;
  std::size_t joints;
  template <class T>
  bool operator()(T const* const* blocks, T* residual) const {
    const auto r = regroup->rows();
    std::vector<T> beta(static_cast<std::size_t>(r), T(0.0));
    for (std::size_t j = 0; j < joints; ++j) {
      T pi[kBodyBlock];
      InertialFromLogCholesky(blocks[2 * j], pi);
      const T* drive = blocks[2 * j + 1];
      const auto column = static_cast<Eigen::Index>(kSerialColumnsPerJoint * j);
      for (Eigen::Index k = 0; k < r; ++k) {
        for (int c = 0; c < kBodyBlock; ++c) {
          const double g = (*regroup)(k, column + c);
          if (g != 0.0) beta[static_cast<std::size_t>(k)] += g * pi[c];
        }
        for (int c = 0; c < kDriveBlock; ++c) {
          const double g = (*regroup)(k, column + kBodyBlock + c);
          if (g != 0.0) beta[static_cast<std::size_t>(k)] += g * drive[c];
        }
      }
    }
    for (Eigen::Index i = 0; i < r; ++i) {
      T sum = T(0.0);
      for (Eigen::Index k = 0; k <= i; ++k) {
        sum += (*whiten)(i, k) * (beta[static_cast<std::size_t>(k)] - (*estimate)(k));
      }
      residual[i] = sum;
    }
    return AllFinite(residual, static_cast<int>(r));
  }
};

// sqrt(w) (pi - pi_urdf) / scale: the URDF's body where the data say nothing.
struct BodyPrior {
  InertialParameters prior, scale;
  double weight;
  template <class T>
  bool operator()(const T* theta, T* residual) const {
    T pi[kBodyBlock];
    InertialFromLogCholesky(theta, pi);
    for (int c = 0; c < kBodyBlock; ++c) residual[c] = T(weight) * (pi[c] - prior[static_cast<std::size_t>(c)]) / scale[static_cast<std::size_t>(c)];
    return AllFinite(residual, kBodyBlock);
  }
};

struct DrivePrior {
  double weight;
  template <class T>
  bool operator()(const T* drive, T* residual) const {
    for (int c = 0; c < kDriveBlock; ++c) residual[c] = T(weight) * drive[c];
    return true;
  }
};

// Scales of a body's parameters: its mass (at least a thousandth of the
// robot's), its mass times a length (its centre's distance, at least 0.1 m)
// and times that length squared.
InertialParameters PriorScale(const InertialParameters& pi, double total_mass) {
  const double m = std::max(pi[0], 1e-3 * total_mass + 1e-6);
  const double length = pi[0] > 0.0 ? std::max(0.1, Eigen::Vector3d(pi[1], pi[2], pi[3]).norm() / pi[0]) : 0.1;
  return {m, m * length, m * length, m * length, m * length * length, m * length * length, m * length * length,
          m * length * length, m * length * length, m * length * length};
}

}  // namespace

ConsistentParameters FitConsistentParameters(const SerialRobot& robot, const BaseParameters& base,
                                             const FitResult& fit, double prior_weight) {
  const std::size_t n = robot.size();
  const auto r = static_cast<Eigen::Index>(base.base.size());
  if (fit.estimates.size() != base.base.size() || fit.covariance.size() != base.base.size() * base.base.size()) {
    throw std::logic_error("FitConsistentParameters: the fit's estimates and covariance are the base parameters'");
  }
  Eigen::VectorXd estimate(r);
  Eigen::MatrixXd covariance(r, r);
  for (Eigen::Index i = 0; i < r; ++i) {
    estimate(i) = fit.estimates[static_cast<std::size_t>(i)].value;
    for (Eigen::Index k = 0; k < r; ++k) covariance(i, k) = fit.covariance[static_cast<std::size_t>(i * r + k)];
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(covariance);
  if (llt.info() != Eigen::Success) throw std::logic_error("FitConsistentParameters: covariance not positive definite");
  const Eigen::MatrixXd whiten = llt.matrixL().solve(Eigen::MatrixXd::Identity(r, r));

  double total_mass = 0.0;
  for (const auto& b : robot.bodies) total_mass += std::max(b[0], 0.0);
  std::vector<std::array<double, kBodyBlock>> bodies(n);
  std::vector<std::array<double, kDriveBlock>> drives(n);
  for (std::size_t j = 0; j < n; ++j) {
    bodies[j] = LogCholeskyFromInertial(robot.bodies[j]);
    drives[j] = {0.0, 0.0, 0.0, 0.0};
  }
  // Drives that lead a base parameter start at its estimate (>= 0 where bounded).
  for (std::size_t k = 0; k < base.base.size(); ++k) {
    const std::size_t column = base.base[k], joint = column / kSerialColumnsPerJoint, c = column % kSerialColumnsPerJoint;
    if (c < kInertialParameters) continue;
    const double v = estimate(static_cast<Eigen::Index>(k));
    drives[joint][c - kInertialParameters] = c - kInertialParameters == 3 ? v : std::max(v, 0.0);
  }
  ceres::Problem problem;
  auto* data = new ceres::DynamicAutoDiffCostFunction<DataCost, 4>(new DataCost{&base.regroup, &whiten, &estimate, n});
  std::vector<double*> blocks;
  for (std::size_t j = 0; j < n; ++j) {
    data->AddParameterBlock(kBodyBlock);
    data->AddParameterBlock(kDriveBlock);
    blocks.push_back(bodies[j].data());
    blocks.push_back(drives[j].data());
  }
  data->SetNumResiduals(static_cast<int>(r));
  problem.AddResidualBlock(data, nullptr, blocks);
  const double w = std::sqrt(prior_weight);
  for (std::size_t j = 0; j < n; ++j) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<BodyPrior, kBodyBlock, kBodyBlock>(
                                 new BodyPrior{robot.bodies[j], PriorScale(robot.bodies[j], total_mass), w}),
                             nullptr, bodies[j].data());
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<DrivePrior, kDriveBlock, kDriveBlock>(new DrivePrior{w}),
                             nullptr, drives[j].data());
    for (int c = 0; c < 3; ++c) problem.SetParameterLowerBound(drives[j].data(), c, 0.0);
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  // Near the boundary of the physical set (a body tending to a flat or
  // massless one) theta runs off to infinity while the cost settles: it
  // stops when an iteration changes the cost (chi^2 / 2) by less than 1e-6 of
  // itself, far below what the data can tell.
  options.max_num_iterations = 5000;
  options.trust_region_strategy_type = ceres::DOGLEG;
  options.use_nonmonotonic_steps = true;
  options.function_tolerance = 1e-6;
  options.gradient_tolerance = 1e-12;
  options.parameter_tolerance = 1e-12;
  options.logging_type = ceres::SILENT;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);

  ConsistentParameters out;
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  out.iterations = static_cast<int>(summary.iterations.size());
  out.termination = summary.message;
  Eigen::VectorXd theta(static_cast<Eigen::Index>(kSerialColumnsPerJoint * n));
  for (std::size_t j = 0; j < n; ++j) {
    InertialParameters pi{};
    InertialFromLogCholesky(bodies[j].data(), pi.data());
    out.bodies.push_back(pi);
    out.drives.push_back({drives[j][0], drives[j][1], drives[j][2], drives[j][3]});
    const auto column = static_cast<Eigen::Index>(kSerialColumnsPerJoint * j);
    for (int c = 0; c < kBodyBlock; ++c) theta(column + c) = pi[static_cast<std::size_t>(c)];
    for (int c = 0; c < kDriveBlock; ++c) theta(column + kBodyBlock + c) = drives[j][static_cast<std::size_t>(c)];
  }
  const Eigen::VectorXd beta = base.regroup * theta;
  out.base.assign(beta.data(), beta.data() + beta.size());
  out.chi2 = (whiten * (beta - estimate)).squaredNorm();
  for (Eigen::Index k = 0; k < r; ++k) {
    const double std = fit.estimates[static_cast<std::size_t>(k)].standard_error;
    const double shift = std > 0.0 ? std::abs(beta(k) - estimate(k)) / std : 0.0;
    if (shift > out.largest_shift) {
      out.largest_shift = shift;
      out.largest_shift_name = base.names[static_cast<std::size_t>(k)];
    }
  }
  return out;
}

}  // namespace driveid
