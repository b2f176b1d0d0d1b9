#include "fit/robot/consistent_parameters.h"

#include <array>
#include <cmath>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <ceres/ceres.h>

#include "core/option_check.h"
#include "models/pseudo_inertia.h"
#include "models/serial_dynamics.h"

namespace driveid {
namespace {

// A body's block: its 10 inertial parameters, in log-Cholesky form; a
// drive's: its terms' values (models/serial_drive_term.h), the nonnegative
// ones bounded at 0.
constexpr int kBodyBlock = static_cast<int>(kInertialParameters), kDriveBlock = static_cast<int>(kSerialDriveTerms);
using DriveBlock = std::array<double, kDriveBlock>;

DriveBlock DriveValues(const SerialDriveParameters& d) {
  DriveBlock out{};
  for (std::size_t k = 0; k < kSerialDriveTerms; ++k) out[k] = d.*(SerialDriveTerms()[k]->member());
  return out;
}
SerialDriveParameters DriveOfValues(const DriveBlock& values) {
  SerialDriveParameters d;
  for (std::size_t k = 0; k < kSerialDriveTerms; ++k) d.*(SerialDriveTerms()[k]->member()) = values[k];
  return d;
}

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
  const Eigen::MatrixXd* regroup;  // r x 15 n
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
  DriveBlock prior;
  double weight;
  template <class T>
  bool operator()(const T* drive, T* residual) const {
    for (int c = 0; c < kDriveBlock; ++c) residual[c] = T(weight) * (drive[c] - prior[static_cast<std::size_t>(c)]);
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

bool ConsistentPrior::IsValid(std::string* error) const {
  return OptionCheck(error).Require(weight > 0.0 && std::isfinite(weight), "‹prior_weight›", weight, "weight > 0");
}

namespace {

// The rows of `regroup` for the base parameters `which`.
Eigen::MatrixXd RowsOf(const Eigen::MatrixXd& regroup, const std::vector<std::size_t>& which) {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(which.size()), regroup.cols());
  for (std::size_t k = 0; k < which.size(); ++k) out.row(static_cast<Eigen::Index>(k)) = regroup.row(static_cast<Eigen::Index>(which[k]));
  return out;
}

ceres::Solver::Options SolverOptions() {
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
  return options;
}

// The data's cost about the free estimates (whitened by their covariance)
// and the held base parameters, each to within 1e-4 of its value.
struct Targets {
  Eigen::MatrixXd regroup_free, whiten, regroup_held, held_whiten;
  Eigen::VectorXd estimate, held_value;
};

Targets MakeTargets(const SerialRobotFitOutput& result) {
  const FitResult& fit = result.fit;
  const auto r = static_cast<Eigen::Index>(result.free.size());
  Targets t;
  t.estimate.resize(r);
  Eigen::MatrixXd covariance(r, r);
  for (Eigen::Index i = 0; i < r; ++i) {
    t.estimate(i) = fit.estimates[static_cast<std::size_t>(i)].value;
    for (Eigen::Index k = 0; k < r; ++k) covariance(i, k) = fit.covariance[static_cast<std::size_t>(i * r + k)];
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(covariance);
  if (llt.info() != Eigen::Success) throw std::logic_error("FitConsistentParameters: covariance not positive definite");
  t.whiten = llt.matrixL().solve(Eigen::MatrixXd::Identity(r, r));
  t.regroup_free = RowsOf(result.base.regroup, result.free);
  std::vector<std::size_t> held;
  for (std::size_t k = 0; k < result.held.size(); ++k) {
    if (!std::isnan(result.held[k])) held.push_back(k);
  }
  t.regroup_held = RowsOf(result.base.regroup, held);
  t.held_value.resize(static_cast<Eigen::Index>(held.size()));
  Eigen::VectorXd diagonal = t.held_value;
  for (std::size_t k = 0; k < held.size(); ++k) {
    const double v = result.held[held[k]];
    t.held_value(static_cast<Eigen::Index>(k)) = v;
    diagonal(static_cast<Eigen::Index>(k)) = 1.0 / (1e-4 * std::max(std::abs(v), 1e-6));
  }
  t.held_whiten = diagonal.asDiagonal();
  return t;
}

// Each body's start and prior: the URDF's; a body the URDF gives no mass is
// unknown, not massless: kUnknownBody, its prior weaker (kUnknownBodyPriorFactor).
struct BodyStarts {
  std::vector<InertialParameters> start;
  std::vector<char> unknown;
  std::vector<std::size_t> unknown_joints;
  double total_mass = 0.0;
};
BodyStarts MakeBodyStarts(const SerialRobot& robot) {
  BodyStarts out;
  for (const InertialParameters& body : robot.bodies) {
    out.unknown.push_back(!(body[0] > 0.0));
    if (out.unknown.back()) out.unknown_joints.push_back(out.start.size());
    out.start.push_back(out.unknown.back() ? kUnknownBody : body);
    out.total_mass += out.start.back()[0];
  }
  return out;
}

}  // namespace

ConsistentParameters FitConsistentParameters(const SerialRobot& robot, const SerialRobotFitOutput& result,
                                             const ConsistentPrior& prior) {
  RequireValid(prior);
  const std::size_t n = robot.size();
  const BaseParameters& base = result.base;
  const FitResult& fit = result.fit;
  const auto r = static_cast<Eigen::Index>(result.free.size());
  if (fit.estimates.size() != result.free.size() || fit.covariance.size() != result.free.size() * result.free.size() ||
      result.held.size() != base.base.size() || (!prior.drives.empty() && prior.drives.size() != n)) {
    throw std::logic_error("FitConsistentParameters: the fit's estimates and covariance are its free base parameters'");
  }
  const Targets targets = MakeTargets(result);
  const Eigen::MatrixXd& regroup_free = targets.regroup_free;
  const Eigen::MatrixXd& whiten = targets.whiten;
  const Eigen::VectorXd& estimate = targets.estimate;
  const std::vector<double> values = result.BaseValues();

  const BodyStarts starts = MakeBodyStarts(robot);
  const std::vector<InertialParameters>& start = starts.start;
  const std::vector<char>& unknown = starts.unknown;
  const double total_mass = starts.total_mass;
  std::vector<std::array<double, kBodyBlock>> bodies(n);
  std::vector<DriveBlock> drives(n);
  for (std::size_t j = 0; j < n; ++j) {
    bodies[j] = LogCholeskyFromInertial(start[j]);
    drives[j] = DriveValues(prior.drives.empty() ? SerialDriveParameters{} : prior.drives[j]);
  }
  // Drives that lead a base parameter start at its estimate (>= 0 where bounded).
  for (std::size_t k = 0; k < base.base.size(); ++k) {
    const std::size_t column = base.base[k], joint = column / kSerialColumnsPerJoint, c = column % kSerialColumnsPerJoint;
    if (c < kInertialParameters) continue;
    const std::size_t term = c - kInertialParameters;
    drives[joint][term] = SerialDriveTerms()[term]->nonnegative() ? std::max(values[k], 0.0) : values[k];
  }
  ceres::Problem problem;
  std::vector<double*> blocks;
  for (std::size_t j = 0; j < n; ++j) {
    blocks.push_back(bodies[j].data());
    blocks.push_back(drives[j].data());
  }
  const auto add_data = [&](const DataCost& cost) {
    if (cost.regroup->rows() == 0) return;
    auto* data = new ceres::DynamicAutoDiffCostFunction<DataCost, 4>(new DataCost(cost));
    for (std::size_t j = 0; j < n; ++j) {
      data->AddParameterBlock(kBodyBlock);
      data->AddParameterBlock(kDriveBlock);
    }
    data->SetNumResiduals(static_cast<int>(cost.regroup->rows()));
    problem.AddResidualBlock(data, nullptr, blocks);
  };
  add_data(DataCost{&regroup_free, &whiten, &estimate, n});
  add_data(DataCost{&targets.regroup_held, &targets.held_whiten, &targets.held_value, n});
  const double w = std::sqrt(prior.weight);
  for (std::size_t j = 0; j < n; ++j) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<BodyPrior, kBodyBlock, kBodyBlock>(new BodyPrior{
                                 start[j], PriorScale(start[j], total_mass),
                                 unknown[j] ? w * std::sqrt(kUnknownBodyPriorFactor) : w}),
                             nullptr, bodies[j].data());
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<DrivePrior, kDriveBlock, kDriveBlock>(
            new DrivePrior{DriveValues(prior.drives.empty() ? SerialDriveParameters{} : prior.drives[j]), w}),
        nullptr, drives[j].data());
    for (int c = 0; c < kDriveBlock; ++c) {
      if (SerialDriveTerms()[static_cast<std::size_t>(c)]->nonnegative()) {
        problem.SetParameterLowerBound(drives[j].data(), c, 0.0);
      }
    }
  }
  const ceres::Solver::Options options = SolverOptions();
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);

  ConsistentParameters out;
  out.unknown_bodies = starts.unknown_joints;
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  out.iterations = static_cast<int>(summary.iterations.size());
  out.termination = summary.message;
  Eigen::VectorXd theta(static_cast<Eigen::Index>(kSerialColumnsPerJoint * n));
  for (std::size_t j = 0; j < n; ++j) {
    InertialParameters pi{};
    InertialFromLogCholesky(bodies[j].data(), pi.data());
    out.bodies.push_back(pi);
    out.drives.push_back(DriveOfValues(drives[j]));
    const auto column = static_cast<Eigen::Index>(kSerialColumnsPerJoint * j);
    for (int c = 0; c < kBodyBlock; ++c) theta(column + c) = pi[static_cast<std::size_t>(c)];
    for (int c = 0; c < kDriveBlock; ++c) theta(column + kBodyBlock + c) = drives[j][static_cast<std::size_t>(c)];
  }
  const Eigen::VectorXd beta = base.regroup * theta, beta_free = regroup_free * theta;
  out.base.assign(beta.data(), beta.data() + beta.size());
  out.chi2 = (whiten * (beta_free - estimate)).squaredNorm();
  for (Eigen::Index k = 0; k < r; ++k) {
    const double std = fit.estimates[static_cast<std::size_t>(k)].standard_error;
    const double shift = std > 0.0 ? std::abs(beta_free(k) - estimate(k)) / std : 0.0;
    if (shift > out.largest_shift) {
      out.largest_shift = shift;
      out.largest_shift_name = base.names[result.free[static_cast<std::size_t>(k)]];
    }
  }
  return out;
}

}  // namespace driveid
