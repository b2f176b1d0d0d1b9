#include "fit/core/least_squares.h"

#include "fit/core/fit_statistics.h"
#include "fit/core/scaled_cost.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <vector>
#include <ceres/ceres.h>
#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"

namespace driveid {

namespace {

// Rows per residual block when a large problem goes to Ceres in chunks.
constexpr int kChunkRows = 8192;

class ProgressCallback final : public ceres::IterationCallback {
 public:
  explicit ProgressCallback(const std::function<void(const FitIteration&)>& progress) : progress_(progress) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
    progress_({s.iteration, s.cost, s.gradient_norm, s.step_norm});
    return ceres::SOLVER_CONTINUE;
  }

 private:
  const std::function<void(const FitIteration&)>& progress_;
};

// Scales of the parameters: the given typical magnitude, else |start|
// (else 1), so that the solver works on z = p / scale of order 1.
std::vector<double> ParameterScales(const std::vector<FitParameter>& parameters) {
  std::vector<double> scale;
  for (const auto& fp : parameters) {
    double s = fp.scale > 0.0 ? fp.scale : std::abs(fp.initial);
    scale.push_back(s > 0.0 ? s : 1.0);
  }
  return scale;
}

ceres::Solver::Options SolverOptions(const FitOptions& options, ProgressCallback& callback) {
  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::DENSE_QR;
  solver_options.max_num_iterations = options.max_iterations;
  // Parameters are scaled by their starting values: a first step may change
  // them by about 100 %, not by orders of magnitude.
  solver_options.initial_trust_region_radius = 1.0;
  // Stopping rules: a relative cost change of 1e-7 is far below statistical
  // significance (the cost itself scatters by sqrt(2/N)), and the simulated
  // models are accurate to about 1e-7 relative, so tighter tolerances only
  // chase integrator noise with rejected steps.
  solver_options.function_tolerance = 1e-7;
  solver_options.gradient_tolerance = 1e-10;
  solver_options.parameter_tolerance = 1e-7;
  solver_options.logging_type = ceres::SILENT;
  solver_options.num_threads = 1;  // deterministic
  if (options.max_seconds > 0.0) solver_options.max_solver_time_in_seconds = options.max_seconds;
  if (options.deadline > 0.0) {
    const double left = std::max(options.deadline - MonotonicSeconds(), 1e-3);
    solver_options.max_solver_time_in_seconds = std::min(solver_options.max_solver_time_in_seconds, left);
  }
  if (options.progress) {
    solver_options.callbacks.push_back(&callback);
    solver_options.update_state_every_iteration = false;
  }
  return solver_options;
}

// Lower bounds of parameters [first, first + count) on the parameter block
// that holds their scaled values.
void SetLowerBounds(ceres::Problem& problem, double* block, std::size_t first, int count,
                    const std::vector<FitParameter>& parameters, const std::vector<double>& scale) {
  for (int j = 0; j < count; ++j) {
    const std::size_t k = first + static_cast<std::size_t>(j);
    if (std::isfinite(parameters[k].lower_bound)) problem.SetParameterLowerBound(block, j, parameters[k].lower_bound / scale[k]);
  }
}

// Refuses a problem without free parameters or with no more rows than them.
void RequireEnoughSamples(int n, int p) {
  if (p == 0) throw IdentificationError("nothing to fit: no free parameters");
  if (n <= p) throw IdentificationError(fmt::format("{} samples cannot determine {} parameters", n, p));
}

// The solver's outcome into `result`; throws when it failed or stopped early
// (but at the time limit: the best point so far, with a warning).
void TakeSummary(const ceres::Solver::Summary& summary, const FitOptions& options, FitResult& result) {
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  result.termination = summary.message;
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  if (summary.termination_type == ceres::FAILURE || summary.termination_type == ceres::USER_FAILURE) {
    throw IdentificationError("solver failed: " + summary.message);
  }
  const bool out_of_time = (options.max_seconds > 0.0 && summary.total_time_in_seconds >= options.max_seconds) ||
                           (options.deadline > 0.0 && MonotonicSeconds() >= options.deadline);
  if (!result.converged && out_of_time) {
    result.warnings.push_back(fmt::format("the solver stopped at the time limit of {:.3g} s (‹max_seconds›) after {} "
                                          "iterations, not converged: the estimates are its best point so far (crop the "
                                          "log with ‹from›/‹to›, or allow more time)",
                                          options.max_seconds, result.iterations));
    return;
  }
  if (!result.converged) {
    throw IdentificationError(fmt::format("solver did not converge in {} iterations ({}): start it closer (values in "
                                          "‹params›), crop a long rest or a settling at the log's start (‹from›), "
                                          "or free fewer terms",
                                          result.iterations, summary.message));
  }
}

// "the model cannot be evaluated at name = value, ...: reason".
[[noreturn]] void ThrowEvaluationFailure(const std::vector<FitParameter>& parameters, const std::vector<double>& physical,
                                         const std::string& reason) {
  std::vector<std::string> values;
  for (std::size_t j = 0; j < parameters.size(); ++j) {
    values.push_back(fmt::format("{} = {:.6g}", parameters[j].name, physical[j]));
  }
  throw IdentificationError(fmt::format("the model cannot be evaluated at {}{}", fmt::join(values, ", "),
                                        reason.empty() ? std::string(" (non-finite residuals)") : ": " + reason));
}

}  // namespace

namespace {

// min 1/2 z'Az - b'z subject to z_j >= lower_j (A positive definite, P x P):
// the unconstrained minimum over the free set with the bound ones held at
// their bounds; the most violated bound joins the set, and a bound whose
// gradient pulls inward leaves it. Returns the number of solves.
int SolveBoundedQuadratic(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, const Eigen::VectorXd& lower,
                          Eigen::VectorXd& z) {
  const Eigen::Index p = b.size();
  std::vector<bool> bound(static_cast<std::size_t>(p), false);
  z = Eigen::VectorXd::Zero(p);
  for (int solve = 1; solve <= 4 * static_cast<int>(p) + 4; ++solve) {
    std::vector<Eigen::Index> open;
    for (Eigen::Index j = 0; j < p; ++j) {
      if (bound[static_cast<std::size_t>(j)]) z(j) = lower(j);
      else open.push_back(j);
    }
    const auto k = static_cast<Eigen::Index>(open.size());
    const Eigen::MatrixXd a_open = a(open, open);
    Eigen::VectorXd b_open = b(open);
    for (Eigen::Index i = 0; i < k; ++i) {
      for (Eigen::Index j = 0; j < p; ++j) {
        if (bound[static_cast<std::size_t>(j)]) b_open(i) -= a(open[static_cast<std::size_t>(i)], j) * z(j);
      }
    }
    const Eigen::VectorXd z_open = a_open.ldlt().solve(b_open);
    for (Eigen::Index i = 0; i < k; ++i) z(open[static_cast<std::size_t>(i)]) = z_open(i);
    Eigen::Index worst = -1;
    double violation = 0.0;
    for (Eigen::Index j : open) {
      if (lower(j) - z(j) > violation) {
        violation = lower(j) - z(j);
        worst = j;
      }
    }
    if (worst >= 0) {
      bound[static_cast<std::size_t>(worst)] = true;
      continue;
    }
    const Eigen::VectorXd gradient = a * z - b;
    Eigen::Index release = -1;
    double pull = 0.0;
    for (Eigen::Index j = 0; j < p; ++j) {
      const double tolerance = 1e-12 * (std::abs(b(j)) + a(j, j) * std::abs(z(j)) + 1e-300);
      if (bound[static_cast<std::size_t>(j)] && gradient(j) < -tolerance && gradient(j) < pull) {
        pull = gradient(j);
        release = j;
      }
    }
    if (release < 0) return solve;
    bound[static_cast<std::size_t>(release)] = false;
  }
  throw IdentificationError("linear least squares: the set of parameters at their bounds did not settle");
}

}  // namespace

FitResult FitLinearLeastSquares(JacobianBlock design, const Eigen::VectorXd& y,
                                const std::vector<FitParameter>& parameters, const std::vector<FitChannel>& channels,
                                const FitOptions& options) {
  const auto n = static_cast<int>(y.size());
  const int p = static_cast<int>(parameters.size());
  RequireEnoughSamples(n, p);
  RequireVaryingMeasurements(channels);
  if (design.values.rows() != n || design.values.cols() != p) {
    throw std::logic_error("FitLinearLeastSquares: the design does not match the parameters or y");
  }
  std::vector<JacobianBlock> blocks;
  blocks.push_back(std::move(design));
  FitResult result;
  // A linear model's Jacobian is the design everywhere: one analysis serves
  // before the solve and at the optimum.
  result.singular_values = RequireIdentifiable(blocks, parameters, options, "from these logs");
  // Normal equations of the column-normalised design (identifiable, so
  // every column is alive and the collinearity index is below 1000).
  const RowMatrix& x = blocks[0].values;
  const Eigen::MatrixXd information = x.transpose() * x;
  const Eigen::VectorXd scale = information.diagonal().cwiseSqrt();
  const Eigen::VectorXd inverse = scale.cwiseInverse();
  const Eigen::MatrixXd a = inverse.asDiagonal() * information * inverse.asDiagonal();
  const Eigen::VectorXd b = inverse.asDiagonal() * (x.transpose() * y);
  Eigen::VectorXd lower(p);
  for (int j = 0; j < p; ++j) lower(j) = parameters[static_cast<std::size_t>(j)].lower_bound * scale(j);
  Eigen::VectorXd z;
  result.iterations = SolveBoundedQuadratic(a, b, lower, z);
  result.converged = true;
  const Eigen::VectorXd estimate = inverse.asDiagonal() * z;
  int at_bound = 0;
  std::vector<double> values(static_cast<std::size_t>(p));
  for (int j = 0; j < p; ++j) {
    values[static_cast<std::size_t>(j)] = estimate(j);
    at_bound += estimate(j) == parameters[static_cast<std::size_t>(j)].lower_bound;
  }
  result.termination = fmt::format("exact linear least squares on the normal equations ({} at a bound)", at_bound);
  Eigen::VectorXd residuals = x * estimate;
  residuals -= y;
  if (!residuals.allFinite()) ThrowEvaluationFailure(parameters, values, "");
  DescribeFit(std::move(blocks), residuals, parameters, values, channels, result, options.clusters);
  return result;
}

namespace {

// The costs of the solve: `rows`' chunks of rows when given, else one
// ScaledBlockCost per block; returns the Schur ordering (the blocks' own
// parameters first, then the shared ones).
std::shared_ptr<ceres::ParameterBlockOrdering> AddCosts(ceres::Problem& problem, BlockResidualModel& model,
                                                        ResidualModel* rows, const std::vector<int>& local_begin,
                                                        int n, const std::vector<double>& scale, std::vector<double>& z,
                                                        const FitOptions& options) {
  auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
  if (rows != nullptr) {
    for (int begin = 0; begin < n; begin += kChunkRows) {
      problem.AddResidualBlock(new ScaledRowsCost(*rows, begin, std::min(n, begin + kChunkRows), scale), nullptr,
                               z.data());
    }
    return ordering;
  }
  const int q = model.shared_count();
  const std::vector<double> shared_scale(scale.begin(), scale.begin() + q);
  for (int b = 0; b < model.block_count(); ++b) {
    const int l = model.local_count(b);
    const auto first = static_cast<std::ptrdiff_t>(local_begin[static_cast<std::size_t>(b)]);
    std::vector<double*> blocks_of_cost;
    if (q > 0) blocks_of_cost.push_back(z.data());
    if (l > 0) {
      blocks_of_cost.push_back(z.data() + first);
      ordering->AddElementToGroup(z.data() + first, 0);  // eliminated first (Schur complement)
    }
    problem.AddResidualBlock(new ScaledBlockCost(model, b, shared_scale,
                                                 std::vector<double>(scale.begin() + first, scale.begin() + first + l),
                                                 options.large),
                             nullptr, blocks_of_cost);
  }
  if (q > 0) ordering->AddElementToGroup(z.data(), 1);
  return ordering;
}

// The one solve driver. The model comes in blocks (a log each, say) whose
// rows depend on the shared parameters and on parameters of their own,
// which Ceres's Schur complement eliminates; a whole ResidualModel is one
// block of shared parameters only, and `whole` then points to it: a large
// one (FitOptions::large) that evaluates row ranges goes to Ceres in chunks
// of rows (no scratch Jacobian of all rows besides Ceres's own; the model's
// memo of its last point answers every chunk from one simulation), and a
// large one is solved on the normal equations (P x P) instead of a QR on a
// copy of the Jacobian (N x P) — the parameters are scaled and identifiable
// (collinearity index < 1000), so squaring the condition number costs no
// accuracy that matters.
// Says `running` true for its lifetime, false at its end (an exception too).
class RunningGuard {
 public:
  explicit RunningGuard(const std::function<void(bool)>& running) : running_(running) {
    if (running_) running_(true);
  }
  ~RunningGuard() {
    if (running_) running_(false);
  }
  RunningGuard(const RunningGuard&) = delete;
  RunningGuard& operator=(const RunningGuard&) = delete;

 private:
  const std::function<void(bool)>& running_;
};

FitResult SolveBlocks(BlockResidualModel& model, ResidualModel* whole, const std::vector<FitParameter>& parameters,
                      const std::vector<FitChannel>& channels, const FitOptions& options) {
  if (options.deadline > 0.0 && MonotonicSeconds() >= options.deadline) {
    throw IdentificationError(fmt::format(
        "the time limit of {:.3g} s (‹max_seconds›) ran out before this fit could start: the estimates so far are "
        "not all a result needs (allow more time, or crop the logs with ‹from›/‹to›)",
        options.max_seconds));
  }
  const RunningGuard guard(options.running);
  const int q = model.shared_count();
  const int block_count = model.block_count();
  const int p = static_cast<int>(parameters.size());
  std::vector<JacobianBlock> blocks(static_cast<std::size_t>(block_count));
  std::vector<int> local_begin;  // first own parameter of each block
  int n = 0, next = q;
  for (int b = 0; b < block_count; ++b) {
    JacobianBlock& block = blocks[static_cast<std::size_t>(b)];
    const int l = model.local_count(b);
    block.row_begin = n;
    for (int j = 0; j < q; ++j) block.columns.push_back(j);
    for (int j = 0; j < l; ++j) block.columns.push_back(next + j);
    block.values.resize(model.block_rows(b), q + l);
    local_begin.push_back(next);
    n += model.block_rows(b);
    next += l;
  }
  if (next != p) throw std::logic_error("FitBlockLeastSquares: parameters do not match the blocks");
  RequireEnoughSamples(n, p);
  RequireVaryingMeasurements(channels);

  const std::vector<double> scale = ParameterScales(parameters);
  std::vector<double> z(static_cast<std::size_t>(p));
  for (std::size_t j = 0; j < z.size(); ++j) z[j] = parameters[j].initial / scale[j];
  Eigen::VectorXd residuals(n);
  std::vector<double> physical(static_cast<std::size_t>(p));
  auto evaluate_at = [&](const std::vector<double>& zz) {
    for (std::size_t j = 0; j < physical.size(); ++j) physical[j] = zz[j] * scale[j];
    for (int b = 0; b < block_count; ++b) {
      JacobianBlock& block = blocks[static_cast<std::size_t>(b)];
      if (!model.EvaluateBlock(b, physical.data(), physical.data() + local_begin[static_cast<std::size_t>(b)],
                               residuals.data() + block.row_begin, block.values.data())) {
        ThrowEvaluationFailure(parameters, physical, model.LastFailure());
      }
    }
  };
  // Structural problems show at the start already: refuse before solving.
  evaluate_at(z);
  RequireIdentifiable(blocks, parameters, options, "from these logs");

  const bool large = whole != nullptr && options.large.IsLarge(static_cast<std::size_t>(n), static_cast<std::size_t>(p));
  FitResult result;
  {
    // The Jacobian's and residuals' storage is Ceres's during the solve.
    for (auto& block : blocks) block.values.resize(0, block.values.cols());
    residuals.resize(0);
    ceres::Problem::Options problem_options;
    problem_options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
    ceres::Problem problem(problem_options);
    const auto ordering =
        AddCosts(problem, model, large && whole->evaluates_rows() ? whole : nullptr, local_begin, n, scale, z, options);
    for (int b = 0; b < block_count; ++b) {
      const auto first = static_cast<std::size_t>(local_begin[static_cast<std::size_t>(b)]);
      SetLowerBounds(problem, z.data() + first, first, model.local_count(b), parameters, scale);
    }
    SetLowerBounds(problem, z.data(), 0, q, parameters, scale);
    ProgressCallback callback(options.progress);
    ceres::Solver::Options solver_options = SolverOptions(options, callback);
    if (large || options.normal_equations) {
      solver_options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
    } else if (ordering->NumGroups() == 2) {
      solver_options.linear_solver_type = ceres::DENSE_SCHUR;
      solver_options.linear_solver_ordering = ordering;
    }
    ceres::Solver::Summary summary;
    ceres::Solve(solver_options, &problem, &summary);
    TakeSummary(summary, options, result);
  }
  for (int b = 0; b < block_count; ++b) {
    JacobianBlock& block = blocks[static_cast<std::size_t>(b)];
    block.values.resize(model.block_rows(b), block.values.cols());
  }
  residuals.resize(n);
  evaluate_at(z);
  if (whole != nullptr) whole->Release();
  result.singular_values = RequireIdentifiable(blocks, parameters, options, "at the optimum");
  DescribeFit(std::move(blocks), residuals, parameters, physical, channels, result, options.clusters);
  return result;
}

}  // namespace

FitResult FitLeastSquares(ResidualModel& model, const std::vector<FitParameter>& parameters,
                          const std::vector<FitChannel>& channels, const FitOptions& options) {
  RequireValid(options);
  WholeModelBlock block(model, static_cast<int>(parameters.size()));
  return SolveBlocks(block, &model, parameters, channels, options);
}

FitResult FitBlockLeastSquares(BlockResidualModel& model, const std::vector<FitParameter>& parameters,
                               const std::vector<FitChannel>& channels, const FitOptions& options) {
  RequireValid(options);
  return SolveBlocks(model, nullptr, parameters, channels, options);
}

void DropParameters(FitResult& fit, const std::vector<bool>& keep) {
  const std::size_t p = fit.estimates.size();
  std::vector<std::size_t> kept;
  for (std::size_t j = 0; j < p; ++j) {
    if (j >= keep.size() || keep[j]) kept.push_back(j);
  }
  const auto shrink = [&](std::vector<double>& matrix) {
    if (matrix.size() != p * p) return;
    std::vector<double> smaller;
    for (std::size_t a : kept) {
      for (std::size_t b : kept) smaller.push_back(matrix[a * p + b]);
    }
    matrix = std::move(smaller);
  };
  shrink(fit.covariance);
  shrink(fit.correlation);
  std::vector<ParameterEstimate> estimates;
  for (std::size_t j : kept) estimates.push_back(fit.estimates[j]);
  fit.estimates = std::move(estimates);
}

}  // namespace driveid
