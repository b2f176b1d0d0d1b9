#include "fit/core/adequacy.h"

#include <algorithm>
#include <cmath>

#include <boost/math/distributions/chi_squared.hpp>
#include <fmt/format.h>

#include "core/errors.h"
#include "fit/core/student_t.h"

namespace driveid {

namespace {

// The refusal's message: the parameters the logs do not determine.
[[noreturn]] void ThrowUndetermined(const std::vector<std::string>& undetermined, const std::vector<std::string>& names,
                                    double max_relative_std, const std::vector<std::string>& context) {
  const char* them = undetermined.size() > 1 ? "them" : "it";
  // A threshold above 100 % is no rule of the user's (a start fit's), not said.
  const std::string rule = max_relative_std <= 1.0
                               ? fmt::format("robust relative std above {:.0f} %, ", 100.0 * max_relative_std)
                               : std::string();
  std::string message = fmt::format(
      "not identifiable: {}: the logs do not determine {} ({}docs/models.md#adequacy): "
      "fix {} in ‹params› and leave {} out of ‹free›, or log motion that excites {}",
      fmt::join(undetermined, "; "), them, rule, them, them, them);
  for (const auto& c : context) message += "\n  warning: " + c;
  throw IdentificationError(message, names);
}

std::string Undetermined(const ParameterEstimate& e) {
  return e.value != 0.0 ? fmt::format("{} = {:.4g} +- {:.2g} (relative std {:.0f} %)", e.name, e.value,
                                      e.standard_error, 100.0 * e.standard_error / std::abs(e.value))
                        : fmt::format("{} = 0 +- {:.2g} (at its bound 0)", e.name, e.standard_error);
}

}  // namespace

void RequireDetermined(FitResult& fit, const std::vector<std::string>& nonnegative, double max_relative_std,
                       const std::vector<std::string>& context, const std::map<std::string, double>& start_values) {
  std::vector<std::string> undetermined, names;
  for (auto& e : fit.estimates) {
    if (std::find(nonnegative.begin(), nonnegative.end(), e.name) == nonnegative.end()) continue;
    if (e.standard_error <= max_relative_std * std::abs(e.value)) continue;
    const auto start = start_values.find(e.name);
    // At its bound: the data push it below 0, and how far above 0 it may be
    // is known: reported as 0 with the one-sided 95 % upper limit as its
    // interval, and the fit stands. A note when that limit rules out the
    // start value (or the start value itself is 0: the user expects none);
    // a warning when it does not (the data cannot tell 0 from the start).
    const bool bounded = e.value == 0.0 && start != start_values.end() && std::isfinite(e.standard_error);
    if (bounded) {
      e.ci95_low = 0.0;
      e.ci95_high = kOneSided95 * e.standard_error;
      const bool rules_out = start->second == 0.0 || e.ci95_high <= max_relative_std * start->second;
      if (rules_out) {
        fit.notes.push_back(
            start->second > 0.0
                ? fmt::format("{} sits at its bound 0 (the data push it below, and rule out its start value {:.3g}): "
                              "reported as 0 with the one-sided 95 % upper limit {:.3g} (1.645 std) as its interval",
                              e.name, start->second, e.ci95_high)
                : fmt::format("{} sits at its bound 0 (the data push it below; its start value is 0): reported as 0 "
                              "with the one-sided 95 % upper limit {:.3g} (1.645 std) as its interval",
                              e.name, e.ci95_high));
      } else {
        fit.warnings.push_back(fmt::format(
            "{} sits at its bound 0: the data push it below, but do not rule out its start value {:.3g}; reported as "
            "0 with the one-sided 95 % upper limit {:.3g} (1.645 std) as its interval [0, {:.3g}]: the logs determine "
            "no more than that bound (log motion that excites it, or fix it in ‹params›)",
            e.name, start->second, e.ci95_high, e.ci95_high));
      }
      continue;
    }
    names.push_back(e.name);
    undetermined.push_back(Undetermined(e));
  }
  if (!undetermined.empty()) ThrowUndetermined(undetermined, names, max_relative_std, context);
}

void BoundOrRefuse(FitResult& fit, const std::vector<std::string>& nonnegative, double max_relative_std,
                   const std::vector<std::string>& context, const std::map<std::string, std::string>& silent) {
  std::vector<std::string> undetermined, names;
  const std::string marker = "bounded only: ";
  for (auto& e : fit.estimates) {
    if (std::find(nonnegative.begin(), nonnegative.end(), e.name) == nonnegative.end()) continue;
    if (e.standard_error <= max_relative_std * std::abs(e.value)) continue;
    const auto why_silent = silent.find(e.name);
    if (std::isfinite(e.standard_error) && e.standard_error > 0.0 && why_silent == silent.end()) {
      // The data bound it: its interval, cut at the bound 0, is the answer;
      // a warning of an earlier pass is replaced.
      const bool at_bound = e.value == 0.0;
      e.ci95_low = 0.0;
      e.ci95_high = at_bound ? kOneSided95 * e.standard_error : e.value + 1.96 * e.standard_error;
      const std::string prefix = marker + e.name + " = ";
      fit.warnings.erase(std::remove_if(fit.warnings.begin(), fit.warnings.end(),
                                        [&](const std::string& w) { return w.rfind(prefix, 0) == 0; }),
                         fit.warnings.end());
      fit.warnings.push_back(fmt::format(
          "{}{:.4g} +- {:.2g} ({}): the logs do not determine it, they bound it: 95 % interval [0, {:.3g}]{}; use "
          "the bound, not the value (log motion that excites it, or fix it in ‹params›; docs/models.md#adequacy)",
          prefix, e.value, e.standard_error,
          at_bound ? std::string("at its bound 0: the data push it below")
                   : fmt::format("relative std {:.0f} %", 100.0 * e.standard_error / std::abs(e.value)),
          e.ci95_high, at_bound ? " (one-sided: 1.645 std)" : ""));
      continue;
    }
    names.push_back(e.name);
    undetermined.push_back(why_silent == silent.end() ? Undetermined(e) : Undetermined(e) + ": " + why_silent->second);
  }
  if (!undetermined.empty()) ThrowUndetermined(undetermined, names, max_relative_std, context);
}

bool MeasurementVaries(const double* measured, int count) {
  if (count <= 1) return false;
  double mean = 0.0, magnitude = 0.0, spread = 0.0;
  for (int k = 0; k < count; ++k) {
    mean += measured[k];
    magnitude = std::max(magnitude, std::abs(measured[k]));
  }
  mean /= count;
  for (int k = 0; k < count; ++k) spread += (measured[k] - mean) * (measured[k] - mean);
  return spread > 0.0 && spread > count * (1e-9 * magnitude) * (1e-9 * magnitude);
}

ChannelStatistics DescribeResiduals(const std::string& name, const double* measured, const double* residuals,
                                    int count) {
  ChannelStatistics stats;
  stats.name = name;
  stats.samples = count;
  if (count <= 0) return stats;
  double ssr = 0.0, lag1 = 0.0, mean = 0.0, spread = 0.0;
  for (int k = 0; k < count; ++k) {
    ssr += residuals[k] * residuals[k];
    if (k > 0) lag1 += residuals[k] * residuals[k - 1];
    if (measured != nullptr) mean += measured[k];
  }
  stats.rmse = std::sqrt(ssr / count);
  stats.autocorrelation = ssr > 0.0 ? lag1 / ssr : 0.0;
  if (measured != nullptr) {
    mean /= count;
    double square = 0.0;
    for (int k = 0; k < count; ++k) {
      spread += (measured[k] - mean) * (measured[k] - mean);
      square += measured[k] * measured[k];
    }
    stats.variation = square > 0.0 ? std::sqrt(spread / square) : 0.0;
    if (square > 0.0) stats.relative_error_percent = 100.0 * std::sqrt(ssr / square);
    stats.fit_percent = MeasurementVaries(measured, count) && stats.variation >= kNearlyConstant
                            ? 100.0 * (1.0 - std::sqrt(ssr / spread))
                            : std::nan("");
  }
  return stats;
}

std::vector<std::string> CheckFitPercent(const FitResult& fit) {
  std::vector<std::string> warnings;
  for (const auto& c : fit.channels) {
    // White residuals at a low fit % mean the channel varies little beyond
    // its noise (a constant torque), not a model that misses something.
    if (c.fit_percent < kLowFitPercent && c.autocorrelation >= kLowFitMinAutocorrelation) {
      warnings.push_back(fmt::format("low fit: {}: fit {:.1f} % (below {:.0f} %, residual lag-1 {:.2f}): the model "
                                     "misses what was measured",
                                     c.name, c.fit_percent, kLowFitPercent, c.autocorrelation));
    }
  }
  return warnings;
}

std::vector<std::string> CheckResidualColour(const FitResult& fit) {
  std::vector<std::string> warnings;
  std::vector<std::string> names;
  for (const auto& e : fit.estimates) {
    if (e.name.find('(') == std::string::npos) names.push_back(e.name);  // not a simulation's initial state
  }
  for (const auto& c : fit.channels) {
    if (!(c.autocorrelation > kColouredResiduals) || c.samples < 20) continue;
    const double rho = std::min(c.autocorrelation, 0.9999);
    warnings.push_back(fmt::format(
        "coloured residuals: {}: residual lag-1 {:.4f} over {} samples (about {:.0f} independent): what the model "
        "leaves is a slow error (a drift, a mode or a torque it does not have), not noise; the intervals of {} "
        "assume it stationary and may be too narrow (compare logs, or plot the residuals)",
        c.name, c.autocorrelation, c.samples, c.samples * (1.0 - rho) / (1.0 + rho), fmt::join(names, ", ")));
  }
  return warnings;
}

std::vector<HeterogeneityTest> TestHeterogeneity(const std::vector<EstimateSet>& logs) {
  std::vector<HeterogeneityTest> tests;
  std::vector<std::string> names;
  for (const auto& log : logs) {
    for (const auto& e : log.estimates) {
      if (std::find(names.begin(), names.end(), e.name) == names.end()) names.push_back(e.name);
    }
  }
  for (const auto& name : names) {
    std::vector<std::pair<double, double>> values;  // estimate, std
    for (const auto& log : logs) {
      for (const auto& e : log.estimates) {
        if (e.name == name && e.standard_error > 0.0 && std::isfinite(e.standard_error)) {
          values.emplace_back(e.value, e.standard_error);
        }
      }
    }
    if (values.size() < 2) continue;
    // Cochran's Q: the inverse-variance weighted spread of the per-log
    // estimates about their pooled mean. If the logs measure one machine and
    // their std are right, Q ~ chi^2 with L - 1 dof; a small p-value says the
    // logs disagree by more than their noise (a changed load, temperature,
    // a model term missing that the logs excite differently). I^2 = (Q - dof)/Q
    // is the share of the spread that is real (Higgins and Thompson 2002).
    double weight_sum = 0.0, weighted = 0.0;
    for (const auto& [b, s] : values) {
      weight_sum += 1.0 / (s * s);
      weighted += b / (s * s);
    }
    const double mean = weighted / weight_sum;
    HeterogeneityTest t;
    t.parameter = name;
    for (const auto& [b, s] : values) t.q += std::pow((b - mean) / s, 2);
    t.dof = static_cast<int>(values.size()) - 1;
    const boost::math::chi_squared distribution(t.dof);
    t.p_value = std::isfinite(t.q) ? boost::math::cdf(boost::math::complement(distribution, t.q)) : 0.0;
    t.i_squared = t.q > 0.0 ? std::max(0.0, (t.q - t.dof) / t.q) : 0.0;
    tests.push_back(t);
  }
  return tests;
}

void AddPerLogFits(FitResult& fit, const std::vector<std::string>& labels,
                   const std::function<std::vector<ParameterEstimate>(std::size_t)>& fit_one) {
  for (std::size_t i = 0; i < labels.size(); ++i) {
    EstimateSet estimates{labels[i], {}, "", 0.0};
    try {
      estimates.estimates = fit_one(i);
    } catch (const std::exception& e) {
      estimates.failure = e.what();
    }
    fit.per_log.push_back(std::move(estimates));
  }
  fit.heterogeneity = TestHeterogeneity(fit.per_log);
  WidenForDisagreement(fit);
  for (auto& w : HeterogeneityWarnings(fit.heterogeneity)) fit.warnings.push_back(std::move(w));
}

void WidenForDisagreement(FitResult& fit) {
  const std::size_t p = fit.estimates.size();
  for (const auto& t : fit.heterogeneity) {
    if (!(t.p_value < kWidenBelowP)) continue;
    std::vector<double> values, variances;
    for (const auto& log : fit.per_log) {
      for (const auto& e : log.estimates) {
        if (e.name == t.parameter && e.standard_error > 0.0 && std::isfinite(e.standard_error)) {
          values.push_back(e.value);
          variances.push_back(e.standard_error * e.standard_error);
        }
      }
    }
    // The between-log variance tau^2 by DerSimonian and Laird's method of
    // moments, tau^2 = (Q - dof) / (S1 - S2/S1) with S_r = sum w_i^r, and
    // the pooled estimate's std under random effects, 1/sqrt(sum 1/(v_i +
    // tau^2)): what the next log of this machine could differ by. Its
    // interval uses Student's t with L - 1 dof, as tau^2 comes from few logs.
    double s1 = 0.0, s2 = 0.0;
    for (double v : variances) {
      s1 += 1.0 / v;
      s2 += 1.0 / (v * v);
    }
    const double tau2 = std::max(0.0, (t.q - t.dof) / (s1 - s2 / s1));
    double w = 0.0;
    for (double v : variances) w += 1.0 / (v + tau2);
    const double spread_std = 1.0 / std::sqrt(w);
    for (std::size_t j = 0; j < p; ++j) {
      ParameterEstimate& e = fit.estimates[j];
      if (e.name != t.parameter || !(spread_std > e.standard_error)) continue;
      const double factor = spread_std / e.standard_error;
      const double quantile = StudentT975(std::max(1, t.dof));
      e.standard_error = spread_std;
      e.ci95_low = e.value - quantile * spread_std;
      e.ci95_high = e.value + quantile * spread_std;
      if (fit.covariance.size() == p * p) {
        for (std::size_t k = 0; k < p; ++k) {
          fit.covariance[j * p + k] *= factor;
          fit.covariance[k * p + j] *= factor;
        }
      }
      fit.notes.push_back(fmt::format(
          "{}: the logs disagree (between-log p = {:.2g}): its std is widened {:.3g}x to the spread between the logs "
          "(random effects, tau = {:.3g}) and its interval uses t with {} dof (docs/models.md#adequacy)",
          e.name, t.p_value, factor, std::sqrt(tau2), t.dof));
    }
  }
}

std::vector<std::string> HeterogeneityWarnings(const std::vector<HeterogeneityTest>& tests) {
  std::vector<std::string> warnings;
  for (const auto& t : tests) {
    if (t.p_value < 1e-3) {
      warnings.push_back(fmt::format("logs disagree: {}: the per-log estimates differ beyond their uncertainty "
                                     "(Cochran Q = {:.3g} on {} dof, p = {:.2g}, I^2 = {:.0f} %): the joint estimate "
                                     "averages different behaviour; compare the per-log table",
                                     t.parameter, t.q, t.dof, t.p_value, 100.0 * t.i_squared));
    }
  }
  return warnings;
}

std::vector<std::string> ProcessingWarnings(const FitResult& fit, double cutoff, const std::string& advice) {
  std::vector<std::string> warnings;
  for (const auto& e : fit.estimates) {
    if (!(e.standard_error > 0.0)) continue;
    std::vector<std::string> moves;
    double largest = 0.0, largest_up_in_std = 0.0;
    for (const auto& other : fit.sensitivity) {
      for (const auto& o : other.estimates) {
        if (o.name != e.name) continue;
        const double move = std::abs(o.value - e.value);
        largest = std::max(largest, move);
        if (other.cutoff > cutoff) {
          largest_up_in_std = std::max(largest_up_in_std, move / std::max(e.standard_error, o.standard_error));
        }
        moves.push_back(fmt::format("{:.4g} at the {}", o.value, other.label));
      }
    }
    if (largest > 2.0 * e.standard_error && largest > 0.01 * kProcessingPercent * std::abs(e.value)) {
      warnings.push_back(fmt::format(
          "processing: {} = {:.4g} +- {:.2g} at the cutoff {:.3g} Hz moves to {} (more than 2 std): the estimate "
          "depends on the differentiation filter by more than 5 %; that spread is added to its std, which says how "
          "far it may be off, not where ({})",
          e.name, e.value, e.standard_error, cutoff, fmt::join(moves, ", "), advice));
    } else if (largest_up_in_std > kProcessingStds) {
      warnings.push_back(fmt::format(
          "processing: {} = {:.4g} +- {:.2g} at the cutoff {:.3g} Hz moves to {}: {:.1f} std at a higher cutoff, "
          "which keeps more of the motion; that spread is added to its std, and other estimates of the fit may "
          "carry an error of that size as well ({})",
          e.name, e.value, e.standard_error, cutoff, fmt::join(moves, ", "), largest_up_in_std, advice));
    }
  }
  return warnings;
}


bool WidenForProcessing(FitResult& fit, double cutoff) {
  std::vector<const EstimateSet*> usable;
  bool moves = false;
  for (const auto& other : fit.sensitivity) {
    if (!other.failure.empty() || other.estimates.empty()) continue;
    usable.push_back(&other);
    for (const auto& e : fit.estimates) {
      for (const auto& o : other.estimates) {
        if (o.name == e.name && std::abs(o.value - e.value) > e.standard_error) moves = true;
      }
    }
  }
  if (!moves) return false;
  const std::vector<ParameterEstimate> before = fit.estimates;
  const double share = 1.0 / std::sqrt(static_cast<double>(usable.size()));
  for (const EstimateSet* other : usable) {
    std::vector<double> gradient;
    for (const auto& e : fit.estimates) {
      double moved = e.value;
      for (const auto& o : other->estimates) {
        if (o.name == e.name) moved = o.value;
      }
      gradient.push_back(share * (moved - e.value));
    }
    AddSystematicCovariance(fit, gradient, 1.0);
  }
  std::vector<std::string> widened;
  for (std::size_t j = 0; j < fit.estimates.size(); ++j) {
    const double factor = before[j].standard_error > 0.0 ? fit.estimates[j].standard_error / before[j].standard_error : 1.0;
    if (factor > 1.05) widened.push_back(fmt::format("{} x{:.2f}", fit.estimates[j].name, factor));
  }
  fit.notes.push_back(fmt::format(
      "processing: the estimates move with the differentiation cutoff (fits at {} around {:.3g} Hz) by more than their "
      "std; that spread is in the covariance and the intervals (std {})",
      usable.size(), cutoff, widened.empty() ? "barely changed" : fmt::format("{}", fmt::join(widened, ", "))));
  return true;
}

void AddSystematicCovariance(FitResult& fit, const std::vector<double>& gradient, double sigma) {
  const std::size_t p = fit.estimates.size();
  if (gradient.size() != p || fit.covariance.size() != p * p || !(sigma > 0.0)) return;
  for (std::size_t j = 0; j < p; ++j) {
    for (std::size_t k = 0; k < p; ++k) fit.covariance[j * p + k] += sigma * sigma * gradient[j] * gradient[k];
  }
  fit.correlation.assign(p * p, 0.0);
  for (std::size_t j = 0; j < p; ++j) {
    ParameterEstimate& e = fit.estimates[j];
    const double std_new = std::sqrt(fit.covariance[j * p + j]);
    const double quantile = e.standard_error > 0.0 ? (e.ci95_high - e.value) / e.standard_error : 1.96;
    e.standard_error = std_new;
    e.ci95_low = e.value - quantile * std_new;
    e.ci95_high = e.value + quantile * std_new;
  }
  for (std::size_t j = 0; j < p; ++j) {
    for (std::size_t k = 0; k < p; ++k) {
      const double s = fit.estimates[j].standard_error * fit.estimates[k].standard_error;
      fit.correlation[j * p + k] = s > 0.0 ? fit.covariance[j * p + k] / s : (j == k ? 1.0 : 0.0);
    }
  }
}

}  // namespace driveid
