#include "fit/least_squares.h"

#include "fit/fit_statistics.h"
#include "fit/scaled_cost.h"
#include "signal/lagged_products.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <complex>
#include <unsupported/Eigen/FFT>
#include <vector>
#include <ceres/ceres.h>
#include <boost/math/distributions/students_t.hpp>
#include <fmt/format.h>

#include "core/errors.h"

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

// The solver's outcome into `result`; throws when it failed or stopped early.
void TakeSummary(const ceres::Solver::Summary& summary, FitResult& result) {
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  result.termination = summary.message;
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  if (summary.termination_type == ceres::FAILURE || summary.termination_type == ceres::USER_FAILURE) {
    throw IdentificationError("solver failed: " + summary.message);
  }
  if (!result.converged) {
    throw IdentificationError(fmt::format("solver did not converge in {} iterations: {}", result.iterations,
                                          summary.message));
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

// Above this bandwidth the lag sum goes through the FFT: the direct sum
// costs n p^2 per lag, and an output-error fit whose residuals have lag-1
// 0.999 asks for thousands of lags (25 000 samples: 3 300 lags, half the
// fit's time).
constexpr int kDirectLagSumMax = 32;

// sum_{l=1..L} c_l (M_l + M_l'), M_l = sum_t g_{t+l} g_t' (p x p), as
// S + S' with S = H' G and H's column i the correlation
// h_i(t) = sum_l c_l g_{t+l,i}, computed for all t at once by the FFT with
// zero padding to N >= n + L (no wrap-around). Equals the direct sum to
// rounding (tests/fit/least_squares_test.cc).
Eigen::MatrixXd LagSumByFft(const Eigen::Ref<const RowMatrix>& g, const std::vector<double>& c) {
  const Eigen::Index n = g.rows();
  const Eigen::Index lags = static_cast<Eigen::Index>(c.size()) - 1;  // c[0] unused
  Eigen::Index size = 1;
  while (size < n + lags) size *= 2;
  Eigen::FFT<double> fft;
  std::vector<double> kernel(static_cast<std::size_t>(size), 0.0);
  // h(t) = sum_l c_l g(t + l) is the circular convolution of g with k(m) = c_{-m}.
  for (Eigen::Index l = 1; l <= lags; ++l) kernel[static_cast<std::size_t>((size - l) % size)] = c[l];
  std::vector<std::complex<double>> kernel_spectrum;
  fft.fwd(kernel_spectrum, kernel);
  Eigen::MatrixXd h(n, g.cols());
  std::vector<double> column(static_cast<std::size_t>(size));
  std::vector<std::complex<double>> spectrum;
  std::vector<double> filtered;
  for (Eigen::Index i = 0; i < g.cols(); ++i) {
    std::fill(column.begin(), column.end(), 0.0);
    for (Eigen::Index t = 0; t < n; ++t) column[static_cast<std::size_t>(t)] = g(t, i);
    fft.fwd(spectrum, column);
    for (std::size_t k = 0; k < spectrum.size(); ++k) spectrum[k] *= kernel_spectrum[k];
    fft.inv(filtered, spectrum);
    for (Eigen::Index t = 0; t < n; ++t) h(t, i) = filtered[static_cast<std::size_t>(t)];
  }
  const Eigen::MatrixXd sum = h.transpose() * g;
  return sum + sum.transpose();
}

// sum_{|l|<=L} w_l gamma_u(l) sum_t G_t' G_{t-l} with Bartlett weights and
// Andrews' AR(1) plug-in bandwidth for lag-1 autocorrelation `lag1`.
Eigen::MatrixXd BartlettCovariance(const Eigen::Ref<const RowMatrix>& g, const Eigen::VectorXd& u, double lag1,
                                   int& bandwidth_out) {
  const Eigen::Index n = u.size();
  const double r0 = u.squaredNorm();
  Eigen::MatrixXd covariance = (r0 / static_cast<double>(n)) * (g.transpose() * g);
  bandwidth_out = 0;
  if (n < 3 || r0 <= 0.0) return covariance;
  // Kept inside (-0.999, 0.999) so that alpha stays finite.
  const double rho = std::clamp(lag1, -0.999, 0.999);
  const double alpha = 4.0 * rho * rho / ((1.0 - rho) * (1.0 - rho) * (1.0 + rho) * (1.0 + rho));
  const double bandwidth = 1.1447 * std::cbrt(alpha * static_cast<double>(n));
  bandwidth_out = static_cast<int>(std::min<double>(std::floor(bandwidth), static_cast<double>(n - 1)));
  if (bandwidth_out > kDirectLagSumMax) {
    // c_l = w_l gamma_l, gamma_l = sum_t u_t u_{t+l} / n.
    std::vector<double> c = LaggedProducts(std::vector<double>(u.data(), u.data() + n), bandwidth_out);
    c[0] = 0.0;
    for (int lag = 1; lag <= bandwidth_out; ++lag) {
      const std::size_t l = static_cast<std::size_t>(lag);
      c[l] = (1.0 - static_cast<double>(lag) / (bandwidth_out + 1.0)) * (c[l] / static_cast<double>(n));
    }
    return covariance + LagSumByFft(g, c);
  }
  for (int lag = 1; lag <= bandwidth_out; ++lag) {
    const double weight = 1.0 - static_cast<double>(lag) / (bandwidth_out + 1.0);
    const double gamma = u.head(n - lag).dot(u.tail(n - lag)) / static_cast<double>(n);
    const Eigen::MatrixXd m = g.bottomRows(n - lag).transpose() * g.topRows(n - lag);
    covariance += weight * gamma * (m + m.transpose());
  }
  return covariance;
}

}  // namespace

LongRunCovariance CalcLongRunCovariance(const Eigen::Ref<const RowMatrix>& jacobian,
                                        const Eigen::Ref<const Eigen::VectorXd>& residuals) {
  RowMatrix g = jacobian;
  return CalcLongRunCovarianceInPlace(g, residuals);
}

LongRunCovariance CalcLongRunCovarianceInPlace(Eigen::Ref<RowMatrix> g,
                                               const Eigen::Ref<const Eigen::VectorXd>& residuals) {
  LongRunCovariance out;
  const Eigen::Index n = residuals.size();
  const Eigen::Index p = g.cols();
  out.covariance = Eigen::MatrixXd::Zero(p, p);
  if (n == 0) return out;
  const double r0 = residuals.squaredNorm();
  if (n >= 3 && r0 > 0.0) out.autocorrelation = residuals.head(n - 1).dot(residuals.tail(n - 1)) / r0;
  // AR(1) prewhitening, exact: with u_0 = e_0 and u_t = e_t - rho e_{t-1},
  // e_t = sum_{k<=t} rho^(t-k) u_k, so the score sum_t J_t' e_t equals
  // sum_s G_s' u_s with G_s = sum_{t>=s} rho^(t-s) J_t (G_s = J_s + rho G_{s+1}).
  // The nearly white u then needs only a short Bartlett window; truncating
  // the slowly decaying autocovariances of e itself under-covers (offset at
  // lag-1 0.99: 86 % instead of 95 %).
  // Prewhitening is phased in between lag-1 0.5 and 0.8: below, the plain
  // Bartlett estimate covers (Monte Carlo) and a small rho would only make u
  // over-differenced, whose negative autocovariances a short window drops.
  // The lag-1 estimate of a short, persistent series is biased low by about
  // (1 + 3 rho) / n (Kendall 1954), and 1/(1 - rho)^2 magnifies that: the
  // prewhitening rho is corrected for it.
  const double weight = std::clamp((out.autocorrelation - 0.5) / 0.3, 0.0, 1.0);
  const double corrected = out.autocorrelation + (1.0 + 3.0 * out.autocorrelation) / static_cast<double>(n);
  const double rho = weight * std::clamp(corrected, -0.99, 0.99);
  Eigen::VectorXd u = residuals;
  for (Eigen::Index t = n - 1; t >= 1; --t) u(t) = residuals(t) - rho * residuals(t - 1);
  for (Eigen::Index t = n - 2; t >= 0; --t) g.row(t) += rho * g.row(t + 1);
  // The window is the one the residuals themselves call for: prewhitened u
  // keeps the rest of their correlation (often negative lags after the
  // AR(1) step), which a window sized for u alone would drop.
  out.covariance = BartlettCovariance(g, u, out.autocorrelation, out.bandwidth);
  return out;
}

double CalcRmsDeviation(const std::vector<double>& values) {
  if (values.empty()) return 0.0;
  const double n = static_cast<double>(values.size());
  double mean = 0.0;
  for (double v : values) mean += v;
  mean /= n;
  double sum = 0.0;
  for (double v : values) sum += (v - mean) * (v - mean);
  return std::sqrt(sum / n);
}

double StudentT975(int dof) {
  if (dof < 1) return std::numeric_limits<double>::infinity();
  const boost::math::students_t distribution(static_cast<double>(dof));
  return boost::math::quantile(boost::math::complement(distribution, 0.025));
}

FitResult FitLeastSquares(ResidualModel& model, const std::vector<FitParameter>& parameters,
                          const std::vector<FitChannel>& channels, const FitOptions& options) {
  const int n = model.residual_count();
  const int p = static_cast<int>(parameters.size());
  RequireEnoughSamples(n, p);
  RequireVaryingMeasurements(channels);

  const std::vector<double> scale = ParameterScales(parameters);
  std::vector<double> z(static_cast<std::size_t>(p));
  for (std::size_t j = 0; j < z.size(); ++j) z[j] = parameters[j].initial / scale[j];

  std::vector<JacobianBlock> blocks(1);  // dense: one block, every column
  for (int j = 0; j < p; ++j) blocks[0].columns.push_back(j);
  blocks[0].values.resize(n, p);
  Eigen::VectorXd residuals(n);
  std::vector<double> physical(static_cast<std::size_t>(p));
  auto evaluate_at = [&](const std::vector<double>& zz) {
    for (std::size_t j = 0; j < physical.size(); ++j) physical[j] = zz[j] * scale[j];
    if (!model.Evaluate(physical.data(), residuals.data(), blocks[0].values.data())) {
      ThrowEvaluationFailure(parameters, physical, model.LastFailure());
    }
  };
  // Structural problems show at the start already: refuse before solving.
  evaluate_at(z);
  RequireIdentifiable(blocks, parameters, options, "from these logs");

  FitResult result;
  {
    // The Jacobian's and residuals' storage is Ceres's during the solve.
    blocks[0].values.resize(0, p);
    residuals.resize(0);
    ceres::Problem::Options problem_options;
    problem_options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
    ceres::Problem problem(problem_options);
    const std::size_t jacobian_bytes = static_cast<std::size_t>(n) * static_cast<std::size_t>(p) * sizeof(double);
    if (jacobian_bytes > kMemoJacobianBytes && model.evaluates_rows()) {
      // A large problem in chunks of rows: Ceres then holds no scratch
      // Jacobian of all rows besides its own, and the model's memo of its
      // last point answers every chunk from one simulation.
      for (int begin = 0; begin < n; begin += kChunkRows) {
        problem.AddResidualBlock(new ScaledRowsCost(model, begin, std::min(n, begin + kChunkRows), scale), nullptr,
                                 z.data());
      }
    } else {
      problem.AddResidualBlock(new ScaledCost(model, scale), nullptr, z.data());
    }
    SetLowerBounds(problem, z.data(), 0, p, parameters, scale);
    ProgressCallback callback(options.progress);
    ceres::Solver::Options solver_options = SolverOptions(options, callback);
    // A large Jacobian: normal equations (P x P) instead of a QR on a copy of
    // it (N x P); the parameters are scaled and identifiable (collinearity
    // index < 1000), so squaring the condition number costs no accuracy
    // that matters.
    if (jacobian_bytes > kMemoJacobianBytes) solver_options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
    ceres::Solver::Summary summary;
    ceres::Solve(solver_options, &problem, &summary);
    TakeSummary(summary, result);
  }
  blocks[0].values.resize(n, p);
  residuals.resize(n);
  evaluate_at(z);
  model.Release();
  result.singular_values = RequireIdentifiable(blocks, parameters, options, "at the optimum");
  DescribeFit(std::move(blocks), residuals, parameters, physical, channels, result);
  return result;
}

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
    Eigen::MatrixXd a_open(k, k);
    Eigen::VectorXd b_open(k);
    for (Eigen::Index i = 0; i < k; ++i) {
      b_open(i) = b(open[static_cast<std::size_t>(i)]);
      for (Eigen::Index j = 0; j < p; ++j) {
        if (bound[static_cast<std::size_t>(j)]) b_open(i) -= a(open[static_cast<std::size_t>(i)], j) * z(j);
      }
      for (Eigen::Index j = 0; j < k; ++j) a_open(i, j) = a(open[static_cast<std::size_t>(i)], open[static_cast<std::size_t>(j)]);
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
  DescribeFit(std::move(blocks), residuals, parameters, values, channels, result);
  return result;
}

FitResult FitBlockLeastSquares(BlockResidualModel& model, const std::vector<FitParameter>& parameters,
                               const std::vector<FitChannel>& channels, const FitOptions& options) {
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
  evaluate_at(z);
  RequireIdentifiable(blocks, parameters, options, "from these logs");

  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  const std::vector<double> shared_scale(scale.begin(), scale.begin() + q);
  auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
  for (int b = 0; b < block_count; ++b) {
    const int l = model.local_count(b);
    const auto first = static_cast<std::size_t>(local_begin[static_cast<std::size_t>(b)]);
    std::vector<double*> blocks_of_cost;
    if (q > 0) blocks_of_cost.push_back(z.data());
    if (l > 0) {
      blocks_of_cost.push_back(z.data() + first);
      ordering->AddElementToGroup(z.data() + first, 0);  // eliminated first (Schur complement)
    }
    problem.AddResidualBlock(
        new ScaledBlockCost(model, b, shared_scale, std::vector<double>(scale.begin() + static_cast<std::ptrdiff_t>(first),
                                                                        scale.begin() + static_cast<std::ptrdiff_t>(first) + l)),
        nullptr, blocks_of_cost);
  }
  if (q > 0) ordering->AddElementToGroup(z.data(), 1);
  for (int b = 0; b < block_count; ++b) {
    const auto first = static_cast<std::size_t>(local_begin[static_cast<std::size_t>(b)]);
    SetLowerBounds(problem, z.data() + first, first, model.local_count(b), parameters, scale);
  }
  SetLowerBounds(problem, z.data(), 0, q, parameters, scale);
  ProgressCallback callback(options.progress);
  ceres::Solver::Options solver_options = SolverOptions(options, callback);
  if (ordering->NumGroups() == 2) {
    solver_options.linear_solver_type = ceres::DENSE_SCHUR;
    solver_options.linear_solver_ordering = ordering;
  }
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options, &problem, &summary);
  FitResult result;
  TakeSummary(summary, result);

  evaluate_at(z);
  result.singular_values = RequireIdentifiable(blocks, parameters, options, "at the optimum");
  DescribeFit(std::move(blocks), residuals, parameters, physical, channels, result);
  return result;
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
