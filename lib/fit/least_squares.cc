#include "fit/least_squares.h"

#include "fit/scaled_cost.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <ceres/ceres.h>
#include <boost/math/distributions/students_t.hpp>
#include <fmt/format.h>

#include "core/errors.h"
#include "fit/adequacy.h"

namespace driveid {
namespace {

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

// Column-normalised Jacobian: each parameter's sensitivity scaled to unit
// length, so that its singular values measure collinearity only.
struct Collinearity {
  Eigen::VectorXd singular_values;  // descending
  Eigen::MatrixXd right_vectors;    // columns = parameter directions
  std::vector<int> dead;            // parameters with no effect at all
};

Collinearity AnalyseCollinearity(const RowMatrix& jacobian) {
  Collinearity result;
  RowMatrix normalised = jacobian;
  for (Eigen::Index j = 0; j < jacobian.cols(); ++j) {
    const double norm = jacobian.col(j).norm();
    if (!(norm > 0.0) || !std::isfinite(norm)) {
      result.dead.push_back(static_cast<int>(j));
      normalised.col(j).setZero();
    } else {
      normalised.col(j) /= norm;
    }
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(normalised, Eigen::ComputeThinV);
  result.singular_values = svd.singularValues();
  result.right_vectors = svd.matrixV();
  return result;
}

// Throws IdentificationError if the Jacobian's columns are (nearly)
// collinear; returns the analysis otherwise.
Collinearity RequireIdentifiable(const RowMatrix& jacobian, const std::vector<FitParameter>& parameters,
                                 const FitOptions& options, const char* where) {
  Collinearity c = AnalyseCollinearity(jacobian);
  std::vector<std::string> involved;
  std::string detail;
  if (!c.dead.empty()) {
    for (int j : c.dead) involved.push_back(parameters[static_cast<std::size_t>(j)].name);
    detail = "the data carry no information on them (zero sensitivity)";
  } else {
    const Eigen::Index p = c.singular_values.size();
    std::vector<double> weight(static_cast<std::size_t>(p), 0.0);
    int weak = 0;
    for (Eigen::Index k = 0; k < p; ++k) {
      if (c.singular_values(k) >= options.identifiability_threshold) continue;
      ++weak;
      for (Eigen::Index j = 0; j < p; ++j) {
        weight[static_cast<std::size_t>(j)] = std::max(weight[static_cast<std::size_t>(j)], std::abs(c.right_vectors(j, k)));
      }
    }
    if (weak == 0) return c;
    for (Eigen::Index j = 0; j < p; ++j) {
      if (weight[static_cast<std::size_t>(j)] > 0.2) involved.push_back(parameters[static_cast<std::size_t>(j)].name);
    }
    detail = fmt::format("{} near-null direction{} (smallest singular value {:.2g} of the normalised Jacobian, "
                         "threshold {:.2g}): only combinations of them are determined",
                         weak, weak > 1 ? "s" : "", c.singular_values(p - 1), options.identifiability_threshold);
  }
  std::string names;
  for (const auto& name : involved) names += (names.empty() ? "" : ", ") + name;
  std::string message = fmt::format("not identifiable {}: {}: {}", where, names, detail);
  if (options.advice) {
    const std::string advice = options.advice(involved);
    if (!advice.empty()) message += "; " + advice;
  }
  throw IdentificationError(message);
}

}  // namespace

namespace {

// sum_{|l|<=L} w_l gamma_u(l) sum_t G_t' G_{t-l} with Bartlett weights and
// Andrews' AR(1) plug-in bandwidth for lag-1 autocorrelation `lag1`.
Eigen::MatrixXd BartlettCovariance(const RowMatrix& g, const Eigen::VectorXd& u, double lag1, int& bandwidth_out) {
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
  LongRunCovariance out;
  const Eigen::Index n = residuals.size();
  const Eigen::Index p = jacobian.cols();
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
  RowMatrix g = jacobian;
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
  if (p == 0) throw IdentificationError("nothing to fit: no free parameters");
  if (n <= p) throw IdentificationError(fmt::format("{} samples cannot determine {} parameters", n, p));

  std::vector<double> scale(static_cast<std::size_t>(p));
  std::vector<double> z(static_cast<std::size_t>(p));
  for (int j = 0; j < p; ++j) {
    const auto& fp = parameters[static_cast<std::size_t>(j)];
    double s = fp.scale > 0.0 ? fp.scale : std::abs(fp.initial);
    if (!(s > 0.0)) s = 1.0;
    scale[static_cast<std::size_t>(j)] = s;
    z[static_cast<std::size_t>(j)] = fp.initial / s;
  }

  RowMatrix jacobian(n, p);
  Eigen::VectorXd residuals(n);
  std::vector<double> physical(static_cast<std::size_t>(p));
  auto evaluate_at = [&](const std::vector<double>& zz) {
    for (int j = 0; j < p; ++j) physical[static_cast<std::size_t>(j)] = zz[static_cast<std::size_t>(j)] * scale[static_cast<std::size_t>(j)];
    if (!model.Evaluate(physical.data(), residuals.data(), jacobian.data())) {
      std::vector<std::string> values;
      for (int j = 0; j < p; ++j) {
        values.push_back(fmt::format("{} = {:.6g}", parameters[static_cast<std::size_t>(j)].name,
                                     physical[static_cast<std::size_t>(j)]));
      }
      const std::string reason = model.LastFailure();
      throw IdentificationError(fmt::format("the model cannot be evaluated at {}{}", fmt::join(values, ", "),
                                            reason.empty() ? std::string(" (non-finite residuals)") : ": " + reason));
    }
  };
  // Structural problems show at the start already: refuse before solving.
  evaluate_at(z);
  RequireIdentifiable(jacobian, parameters, options, "from these logs");

  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  problem.AddResidualBlock(new ScaledCost(model, scale), nullptr, z.data());
  for (int j = 0; j < p; ++j) {
    const double lower = parameters[static_cast<std::size_t>(j)].lower_bound;
    if (std::isfinite(lower)) problem.SetParameterLowerBound(z.data(), j, lower / scale[static_cast<std::size_t>(j)]);
  }
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
  ProgressCallback callback(options.progress);
  if (options.progress) {
    solver_options.callbacks.push_back(&callback);
    solver_options.update_state_every_iteration = false;
  }
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options, &problem, &summary);

  FitResult result;
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

  evaluate_at(z);
  const Collinearity collinearity = RequireIdentifiable(jacobian, parameters, options, "at the optimum");
  result.cost = 0.5 * residuals.squaredNorm();
  result.singular_values.assign(collinearity.singular_values.data(),
                                collinearity.singular_values.data() + collinearity.singular_values.size());

  // Covariance of the (unweighted) least-squares estimate, robust to
  // residuals correlated in time (docs/models.md#identification): sandwich
  // A B A, A = (J'J)^-1, B = sum over channels of the long-run covariance
  //   B_c = N/(N-P) sum_{|l|<=L} (1 - |l|/(L+1)) gamma_c(l) sum_t J_t' J_{t-l},
  // gamma_c(l) the residuals' autocovariance (Bartlett weights; persistent
  // residuals AR(1)-prewhitened first, see CalcLongRunCovariance),
  // with Andrews' (1991) AR(1) plug-in bandwidth for the Bartlett kernel,
  //   L = 1.1447 (alpha N_c)^(1/3),  alpha = 4 rho^2 / ((1 - rho)^2 (1 + rho)^2),
  // rho the residuals' lag-1 autocorrelation. Uncorrelated residuals give
  // L ~ 0: the per-channel s_c^2 J_c'J_c of white noise.
  const Eigen::VectorXd column_scale = jacobian.colwise().norm().transpose();
  const RowMatrix scaled = jacobian * column_scale.cwiseInverse().asDiagonal();
  const Eigen::MatrixXd information = scaled.transpose() * scaled;
  const Eigen::MatrixXd inverse = information.ldlt().solve(Eigen::MatrixXd::Identity(p, p));
  Eigen::MatrixXd middle = Eigen::MatrixXd::Zero(p, p);
  const double dof_fraction = static_cast<double>(n - p) / n;
  std::vector<FitChannel> all = channels;
  if (all.empty()) all.push_back({"residual", 0, n, nullptr});
  for (const auto& channel : all) {
    const auto rows = scaled.middleRows(channel.begin, channel.count);
    const auto r = residuals.segment(channel.begin, channel.count);
    const double ssr = r.squaredNorm();
    const double variance = ssr / (channel.count * dof_fraction);
    const Eigen::MatrixXd white = variance * rows.transpose() * rows;
    const LongRunCovariance hac = CalcLongRunCovariance(rows, r);
    const Eigen::MatrixXd robust = hac.covariance / dof_fraction;
    middle += robust;

    // Residuals here are model - measured; the statistics use measured - model.
    const Eigen::VectorXd measured_minus_model = -r;
    ChannelStatistics stats =
        DescribeResiduals(channel.name, channel.measured, measured_minus_model.data(), channel.count);
    stats.autocorrelation = hac.autocorrelation;
    stats.bandwidth = hac.bandwidth;
    stats.inflation = white.trace() > 0.0 ? std::sqrt(std::max(0.0, robust.trace() / white.trace())) : 1.0;
    result.channels.push_back(stats);
  }
  Eigen::MatrixXd covariance = inverse * middle * inverse;
  covariance = column_scale.cwiseInverse().asDiagonal() * covariance * column_scale.cwiseInverse().asDiagonal();

  // The interval's quantile: Student's t with the effective number of
  // samples, N_eff = sum_c N_c (1 - rho_c) / (1 + rho_c) for lag-1 rho_c > 0
  // (an AR(1) channel carries that much independent information), less P.
  // A long-run covariance from few effective samples is itself uncertain
  // (step fit at lag-1 0.9, 200 samples: N_eff ~ 10, t 2.3 instead of 1.97).
  double effective = 0.0;
  for (const auto& c : result.channels) {
    // With Kendall's small-sample correction, as for the prewhitening.
    const double rho = std::clamp(c.autocorrelation + (1.0 + 3.0 * c.autocorrelation) / std::max(c.samples, 1), 0.0,
                                  0.999);
    effective += c.samples * (1.0 - rho) / (1.0 + rho);
  }
  const double t = StudentT975(std::max(1, static_cast<int>(std::floor(effective)) - p));
  for (int j = 0; j < p; ++j) {
    ParameterEstimate e;
    e.name = parameters[static_cast<std::size_t>(j)].name;
    e.value = z[static_cast<std::size_t>(j)] * scale[static_cast<std::size_t>(j)];
    e.standard_error = std::sqrt(std::max(0.0, covariance(j, j)));
    e.ci95_low = e.value - t * e.standard_error;
    e.ci95_high = e.value + t * e.standard_error;
    result.estimates.push_back(e);
  }
  result.covariance.resize(static_cast<std::size_t>(p * p));
  for (int i = 0; i < p; ++i) {
    for (int j = 0; j < p; ++j) result.covariance[static_cast<std::size_t>(i * p + j)] = covariance(i, j);
  }
  result.correlation.resize(static_cast<std::size_t>(p * p));
  for (int i = 0; i < p; ++i) {
    for (int j = 0; j < p; ++j) {
      const double denominator = std::sqrt(covariance(i, i) * covariance(j, j));
      result.correlation[static_cast<std::size_t>(i * p + j)] = denominator > 0.0 ? covariance(i, j) / denominator : 0.0;
    }
  }
  result.warnings = CheckFitPercent(result);  // adequacy.h; fits add their own checks
  return result;
}

}  // namespace driveid
