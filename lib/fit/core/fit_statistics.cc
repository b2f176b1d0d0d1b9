#include "fit/core/fit_statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "core/errors.h"
#include "fit/core/adequacy.h"
#include "fit/core/covariance.h"

namespace driveid {
namespace {

std::size_t Index(Eigen::Index i) { return static_cast<std::size_t>(i); }

// Euclidean norm of every parameter's column over all blocks.
Eigen::VectorXd ColumnNorms(const std::vector<JacobianBlock>& blocks, int p) {
  Eigen::VectorXd squared = Eigen::VectorXd::Zero(p);
  for (const auto& b : blocks) {
    const Eigen::VectorXd block = b.values.colwise().squaredNorm().transpose();
    for (std::size_t k = 0; k < b.columns.size(); ++k) squared(b.columns[k]) += block(static_cast<Eigen::Index>(k));
  }
  return squared.cwiseSqrt();
}

// Divides the block's columns by `norm` in place (0 where a column is dead).
void Normalise(JacobianBlock& b, const Eigen::VectorXd& norm) {
  for (std::size_t k = 0; k < b.columns.size(); ++k) {
    const double n = norm(b.columns[k]);
    if (n > 0.0 && std::isfinite(n)) b.values.col(static_cast<Eigen::Index>(k)) /= n;
    else b.values.col(static_cast<Eigen::Index>(k)).setZero();
  }
}

// Adds m (over the block's columns) into the P x P `target`.
void Scatter(const Eigen::MatrixXd& m, const std::vector<int>& columns, Eigen::MatrixXd& target) {
  for (std::size_t i = 0; i < columns.size(); ++i) {
    for (std::size_t j = 0; j < columns.size(); ++j) {
      target(columns[i], columns[j]) += m(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
    }
  }
}

// J'J of the column-normalised Jacobian, P x P: D^-1 (J'J) D^-1 with D the
// column norms (dead columns 0), without a normalised copy of J.
Eigen::MatrixXd NormalisedInformation(const std::vector<JacobianBlock>& blocks, const Eigen::VectorXd& norm, int p) {
  Eigen::MatrixXd information = Eigen::MatrixXd::Zero(p, p);
  for (const auto& b : blocks) Scatter(b.values.transpose() * b.values, b.columns, information);
  Eigen::VectorXd inverse(p);
  for (int j = 0; j < p; ++j) inverse(j) = norm(j) > 0.0 && std::isfinite(norm(j)) ? 1.0 / norm(j) : 0.0;
  return inverse.asDiagonal() * information * inverse.asDiagonal();
}

// The block holding a channel's rows (a channel never spans blocks).
JacobianBlock& BlockOf(std::vector<JacobianBlock>& blocks, const FitChannel& c) {
  for (auto& b : blocks) {
    if (c.begin >= b.row_begin && c.begin + c.count <= b.row_begin + static_cast<int>(b.values.rows())) return b;
  }
  throw std::logic_error("fit channel '" + c.name + "' spans Jacobian blocks");
}

// A cluster's score g_s = sum over its rows of J_t' r_t and information
// H_s = sum J_t' J_t on the normalised Jacobian.
void ClusterTerms(const std::vector<JacobianBlock>& blocks, const Eigen::VectorXd& residuals,
                  const std::vector<RowRange>& cluster, Eigen::VectorXd& score, Eigen::MatrixXd& information) {
  score.setZero();
  information.setZero();
  for (const RowRange& range : cluster) {
    for (const auto& b : blocks) {
      const int begin = std::max(range.begin, b.row_begin);
      const int end = std::min(range.begin + range.count, b.row_begin + static_cast<int>(b.values.rows()));
      if (end <= begin) continue;
      const auto rows = b.values.middleRows(begin - b.row_begin, end - begin);
      const Eigen::VectorXd part = rows.transpose() * residuals.segment(begin, end - begin);
      const Eigen::MatrixXd h = rows.transpose() * rows;
      for (std::size_t k = 0; k < b.columns.size(); ++k) {
        score(b.columns[k]) += part(static_cast<Eigen::Index>(k));
      }
      Scatter(h, b.columns, information);
    }
  }
}

// Cluster-robust covariance on the normalised Jacobian (information A).
// CR1 for every parameter: A^-1 (G/(G-1) sum_s g_s g_s') A^-1. For the
// parameters that several clusters inform, the delete-one-cluster
// jackknife (CR3), which CR1 understates when each cluster also has
// parameters of its own (a segment's initial state) and G is a few dozen:
// delta_s = (A - H_s)^-1 g_s, the linearised change of the estimate without
// cluster s (its own parameters, informed by it alone, left out), and
// (G-1)/G sum_s (delta_s - mean)(delta_s - mean)'.
Eigen::MatrixXd ClusterCovariance(const std::vector<JacobianBlock>& blocks, const Eigen::VectorXd& residuals,
                                  const std::vector<std::vector<RowRange>>& clusters, const Eigen::MatrixXd& a,
                                  const Eigen::MatrixXd& inverse) {
  const Eigen::Index p = a.rows();
  const double g = static_cast<double>(clusters.size());
  std::vector<Eigen::VectorXd> deltas;
  std::vector<std::vector<Eigen::Index>> kept;
  Eigen::MatrixXd middle = Eigen::MatrixXd::Zero(p, p), h(p, p);
  Eigen::VectorXd score(p);
  std::vector<bool> own_anywhere(static_cast<std::size_t>(p), false);
  for (const auto& cluster : clusters) {
    ClusterTerms(blocks, residuals, cluster, score, h);
    middle += score * score.transpose();
    std::vector<Eigen::Index> rest;  // parameters informed by other clusters too
    for (Eigen::Index j = 0; j < p; ++j) {
      if (!(a(j, j) > 0.0)) continue;
      if (h(j, j) >= (1.0 - 1e-9) * a(j, j)) own_anywhere[static_cast<std::size_t>(j)] = true;
      else rest.push_back(j);
    }
    const Eigen::MatrixXd reduced = a(rest, rest) - h(rest, rest);
    deltas.push_back(reduced.ldlt().solve(Eigen::VectorXd(score(rest))));
    kept.push_back(std::move(rest));
  }
  Eigen::MatrixXd covariance = inverse * (g > 1.0 ? middle * (g / (g - 1.0)) : middle) * inverse;
  if (g < 2.0) return covariance;
  // The jackknife over the parameters every cluster keeps.
  std::vector<Eigen::Index> shared;
  for (Eigen::Index j = 0; j < p; ++j) {
    if (a(j, j) > 0.0 && !own_anywhere[static_cast<std::size_t>(j)]) shared.push_back(j);
  }
  const auto q = static_cast<Eigen::Index>(shared.size());
  Eigen::MatrixXd d(static_cast<Eigen::Index>(deltas.size()), q);
  for (std::size_t s = 0; s < deltas.size(); ++s) {
    for (Eigen::Index i = 0; i < q; ++i) {
      const auto at = std::find(kept[s].begin(), kept[s].end(), shared[static_cast<std::size_t>(i)]);
      d(static_cast<Eigen::Index>(s), i) = deltas[s](at - kept[s].begin());
    }
  }
  const Eigen::MatrixXd centred = d.rowwise() - d.colwise().mean();
  const Eigen::MatrixXd jackknife = (g - 1.0) / g * (centred.transpose() * centred);
  for (Eigen::Index i = 0; i < q; ++i) {
    for (Eigen::Index k = 0; k < q; ++k) covariance(shared[static_cast<std::size_t>(i)], shared[static_cast<std::size_t>(k)]) = jackknife(i, k);
  }
  return covariance;
}

}  // namespace

std::vector<double> RequireIdentifiable(const std::vector<JacobianBlock>& blocks,
                                        const std::vector<FitParameter>& parameters, const FitOptions& options,
                                        const char* where) {
  const int p = static_cast<int>(parameters.size());
  const Eigen::VectorXd norm = ColumnNorms(blocks, p);
  std::vector<std::string> involved;
  std::string detail;
  // Singular values of the normalised Jacobian: square roots of the
  // eigenvalues of its J'J (accurate far below the 1e-3 threshold).
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(NormalisedInformation(blocks, norm, p));
  std::vector<double> singular(Index(p));
  for (int k = 0; k < p; ++k) singular[Index(k)] = std::sqrt(std::max(0.0, eigen.eigenvalues()(p - 1 - k)));
  for (int j = 0; j < p; ++j) {
    if (!(norm(j) > 0.0) || !std::isfinite(norm(j))) involved.push_back(parameters[Index(j)].name);
  }
  if (!involved.empty()) {
    detail = "the data carry no information on them (zero sensitivity)";
  } else {
    std::vector<double> weight(Index(p), 0.0);
    int weak = 0;
    for (int k = 0; k < p; ++k) {  // eigenvalues ascending: the weakest first
      if (singular[Index(p - 1 - k)] >= options.identifiability_threshold) continue;
      ++weak;
      for (int j = 0; j < p; ++j) {
        weight[Index(j)] = std::max(weight[Index(j)], std::abs(eigen.eigenvectors()(j, k)));
      }
    }
    if (weak == 0) return singular;
    for (int j = 0; j < p; ++j) {
      if (weight[Index(j)] > 0.2) involved.push_back(parameters[Index(j)].name);
    }
    detail = fmt::format("{} near-null direction{} (smallest singular value {:.2g} of the normalised Jacobian, "
                         "threshold {:.2g}): only combinations of them are determined",
                         weak, weak > 1 ? "s" : "", singular.back(), options.identifiability_threshold);
  }
  std::string message = fmt::format("not identifiable {}: {}: {}", where, fmt::join(involved, ", "), detail);
  if (options.advice) {
    const std::string advice = options.advice(involved);
    if (!advice.empty()) message += "; " + advice;
  }
  throw IdentificationError(message, involved);
}

namespace {

// Statistics that overflowed (data near the end of double's range, a design
// that overflows when normalised) are not a fit: refused, never written.
void RequireFiniteStatistics(const std::vector<FitChannel>& channels, const FitResult& result) {
  for (std::size_t c = 0; c < result.channels.size(); ++c) {
    const ChannelStatistics& s = result.channels[c];
    if (std::isfinite(s.rmse) && std::isfinite(s.autocorrelation) && std::isfinite(s.inflation)) continue;
    std::string range;
    if (channels[c].measured != nullptr && channels[c].count > 0) {
      const auto [low, high] = std::minmax_element(channels[c].measured, channels[c].measured + channels[c].count);
      range = fmt::format(" (measured from {:.4g} to {:.4g})", *low, *high);
    }
    throw IdentificationError(fmt::format("{}: the fit's statistics are not finite (rmse {}, residual lag-1 {}){}: the "
                                          "numbers overflow double precision; rescale the data",
                                          s.name, s.rmse, s.autocorrelation, range));
  }
  for (const auto& e : result.estimates) {
    if (!std::isfinite(e.value) || !std::isfinite(e.standard_error)) {
      throw IdentificationError(fmt::format("{}: {} +- {}: not finite (the design overflows when normalised); "
                                            "rescale the data",
                                            e.name, e.value, e.standard_error));
    }
  }
}

}  // namespace

void RequireVaryingMeasurements(const std::vector<FitChannel>& channels) {
  if (channels.empty()) return;
  std::vector<std::string> constant;
  for (const auto& c : channels) {
    if (c.measured == nullptr || MeasurementVaries(c.measured, c.count)) return;
    constant.push_back(c.count > 0 ? fmt::format("{} ({:.6g} throughout)", c.name, c.measured[0]) : c.name);
  }
  throw IdentificationError(fmt::format("nothing to identify: the measured {} do{} not vary",
                                        fmt::join(constant, ", "), constant.size() == 1 ? "es" : ""));
}

void DescribeFit(std::vector<JacobianBlock> blocks, const Eigen::VectorXd& residuals,
                 const std::vector<FitParameter>& parameters, const std::vector<double>& values,
                 const std::vector<FitChannel>& channels, FitResult& result,
                 const std::vector<std::vector<RowRange>>& clusters) {
  const int p = static_cast<int>(parameters.size());
  const int n = static_cast<int>(residuals.size());
  result.cost = 0.5 * residuals.squaredNorm();

  // Covariance of the (unweighted) least-squares estimate, robust to
  // residuals correlated in time (docs/models.md#identification): sandwich
  // A B A, A = (J'J)^-1, B = sum over channels of the long-run covariance
  //   B_c = N/(N-P) sum_{|l|<=L} (1 - |l|/(L+1)) gamma_c(l) sum_t J_t' J_{t-l},
  // gamma_c(l) the residuals' autocovariance (Bartlett weights; persistent
  // residuals AR(1)-prewhitened first, see CalcLongRunCovariance),
  // with Andrews' (1991) AR(1) plug-in bandwidth for the Bartlett kernel,
  //   L = 1.1447 (alpha N_c)^(1/3),  alpha = 4 rho^2 / ((1 - rho)^2 (1 + rho)^2),
  // rho the residuals' lag-1 autocorrelation. Uncorrelated residuals give
  // L ~ 0: the per-channel s_c^2 J_c'J_c of white noise. Each channel's rows
  // lie in one block, so its terms involve only that block's columns.
  const Eigen::VectorXd column_scale = ColumnNorms(blocks, p);
  const Eigen::MatrixXd information = NormalisedInformation(blocks, column_scale, p);
  for (auto& b : blocks) Normalise(b, column_scale);
  const Eigen::MatrixXd inverse = information.ldlt().solve(Eigen::MatrixXd::Identity(p, p));
  // Clusters: from the rows before the channels' rows are prewhitened below.
  const Eigen::MatrixXd cluster_covariance =
      clusters.empty() ? Eigen::MatrixXd() : ClusterCovariance(blocks, residuals, clusters, information, inverse);
  Eigen::MatrixXd middle = Eigen::MatrixXd::Zero(p, p);
  const double dof_fraction = static_cast<double>(n - p) / n;
  std::vector<FitChannel> all = channels;
  if (all.empty()) all.push_back({"residual", 0, n, nullptr});
  for (const auto& channel : all) {
    JacobianBlock& block = BlockOf(blocks, channel);
    auto rows = block.values.middleRows(channel.begin - block.row_begin, channel.count);
    const auto r = residuals.segment(channel.begin, channel.count);
    const double variance = r.squaredNorm() / (channel.count * dof_fraction);
    const double white_trace = variance * rows.squaredNorm();
    // The channel's rows are not needed after this: prewhitened in place.
    const LongRunCovariance hac = CalcLongRunCovarianceInPlace(rows, r);
    const Eigen::MatrixXd robust = hac.covariance / dof_fraction;
    Scatter(robust, block.columns, middle);

    // Residuals here are model - measured; the statistics use measured - model.
    const Eigen::VectorXd measured_minus_model = -r;
    ChannelStatistics stats =
        DescribeResiduals(channel.name, channel.measured, measured_minus_model.data(), channel.count);
    stats.autocorrelation = hac.autocorrelation;
    stats.bandwidth = hac.bandwidth;
    stats.inflation = white_trace > 0.0 ? std::sqrt(std::max(0.0, robust.trace() / white_trace)) : 1.0;
    result.channels.push_back(stats);
  }
  Eigen::MatrixXd covariance = clusters.empty() ? Eigen::MatrixXd(inverse * middle * inverse) : cluster_covariance;
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
  const double t = clusters.empty() ? StudentT975(std::max(1, static_cast<int>(std::floor(effective)) - p))
                                    : StudentT975(std::max(1, static_cast<int>(clusters.size()) - 1));
  result.estimates.clear();
  for (int j = 0; j < p; ++j) {
    ParameterEstimate e;
    e.name = parameters[Index(j)].name;
    e.value = values[Index(j)];
    e.standard_error = std::sqrt(std::max(0.0, covariance(j, j)));
    e.ci95_low = e.value - t * e.standard_error;
    e.ci95_high = e.value + t * e.standard_error;
    result.estimates.push_back(e);
  }
  result.covariance.resize(Index(p) * Index(p));
  result.correlation.resize(Index(p) * Index(p));
  for (int i = 0; i < p; ++i) {
    for (int j = 0; j < p; ++j) {
      result.covariance[Index(i) * Index(p) + Index(j)] = covariance(i, j);
      const double denominator = std::sqrt(covariance(i, i) * covariance(j, j));
      result.correlation[Index(i) * Index(p) + Index(j)] = denominator > 0.0 ? covariance(i, j) / denominator : 0.0;
    }
  }
  RequireFiniteStatistics(all, result);
  result.warnings = CheckFitPercent(result);  // adequacy.h; fits add their own checks
  // Cluster-robust intervals (segments) do not assume stationary residuals.
  if (clusters.empty()) {
    for (auto& w : CheckResidualColour(result)) result.warnings.push_back(std::move(w));
  }
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

}  // namespace driveid
