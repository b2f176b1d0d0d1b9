#include "fit/axis/axis_oe_fit.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"
#include "fit/core/adequacy.h"
#include "fit/axis/axis_adequacy.h"
#include "fit/axis/axis_fit.h"
#include "models/axis_term.h"
#include "sim/axis_simulator.h"

namespace driveid {

bool AxisOeOptions::IsValid(std::string* error) const { return OptionCheck(error).Nested(fit); }
namespace {

// Samples over which the start rate is taken when qd is not logged.
constexpr std::size_t kStartRateSamples = 10;

// One log's channels: position, and rate if logged; weights 1 / RMS deviation.
struct OeLog {
  const AxisLog* log = nullptr;
  double q0 = 0.0, v0 = 0.0;
  double position_weight = 1.0, rate_weight = 0.0;  // rate_weight 0: no rate channel
  int first_row = 0;
  std::vector<std::size_t> rows;                         // the measured rows (AxisLog::measured)
  std::vector<double> weighted_position, weighted_rate;  // measured x weight, for fit %
};

class AxisOeResiduals final : public ResidualModel {
 public:
  AxisOeResiduals(std::vector<OeLog>& logs, const AxisParameters& fixed, std::vector<int> terms,
                  double position_tolerance, double rate_tolerance)
      : logs_(logs), params_(fixed), terms_(terms), simulator_(std::move(terms), position_tolerance, rate_tolerance) {
    for (auto& l : logs_) {
      l.first_row = rows_;
      rows_ += static_cast<int>(l.rows.size()) * (l.rate_weight > 0.0 ? 2 : 1);
    }
  }
  int residual_count() const override { return rows_; }

  bool Evaluate(const double* parameters, double* residuals, double* jacobian) override {
    const std::size_t p = terms_.size();
    Set(parameters);
    try {
      for (const auto& l : logs_) {
        const AxisLog& log = *l.log;
        simulator_.Simulate(params_, log.time, log.force, l.q0, l.v0, jacobian != nullptr, &response_);
        const std::size_t n = l.rows.size(), base = static_cast<std::size_t>(l.first_row);
        for (std::size_t i = 0; i < n; ++i) {
          const std::size_t k = l.rows[i];
          residuals[base + i] = l.position_weight * (response_.position[k] - log.position[k]);
          if (l.rate_weight > 0.0) residuals[base + n + i] = l.rate_weight * (response_.rate[k] - log.rate[k]);
          if (jacobian == nullptr) continue;
          for (std::size_t j = 0; j < p; ++j) {
            jacobian[(base + i) * p + j] = l.position_weight * response_.position_sensitivity[k * p + j];
            if (l.rate_weight > 0.0) {
              jacobian[(base + n + i) * p + j] = l.rate_weight * response_.rate_sensitivity[k * p + j];
            }
          }
        }
      }
    } catch (const IdentificationError& e) {
      last_failure_ = e.what();
      return false;
    }
    for (int i = 0; i < rows_; ++i) {
      if (!std::isfinite(residuals[i])) {
        last_failure_ = "the simulated position is not finite";
        return false;
      }
    }
    last_failure_.clear();
    return true;
  }
  std::string LastFailure() const override { return last_failure_; }

  void Simulate(const double* parameters, std::size_t i, std::vector<double>* position, std::vector<double>* rate) {
    Set(parameters);
    const OeLog& l = logs_[i];
    simulator_.Simulate(params_, l.log->time, l.log->force, l.q0, l.v0, false, &response_);
    *position = response_.position;
    *rate = response_.rate;
  }
  const AxisParameters& params() const { return params_; }

 private:
  void Set(const double* parameters) {
    for (std::size_t j = 0; j < terms_.size(); ++j) ModelValue(AxisTermRow(static_cast<std::size_t>(terms_[j])), params_) = parameters[j];
  }

  std::vector<OeLog>& logs_;
  AxisParameters params_;
  std::vector<int> terms_;
  AxisSimulator simulator_;
  AxisResponse response_;
  int rows_ = 0;
  std::string last_failure_;
};

std::string OeAdvice(const std::vector<std::string>& involved) {
  std::vector<std::string> advice;
  const auto has = [&](const char* key) { return std::find(involved.begin(), involved.end(), key) != involved.end(); };
  if (has("offset") && has("coulomb")) {
    advice.push_back("offset and Coulomb friction separate only with motion in both directions");
  }
  if (has("coulomb_pos") && has("coulomb_neg") && has("offset")) {
    advice.push_back("an offset and both Coulomb directions span the same torque: fix the offset");
  }
  if (has("inertia")) advice.push_back("the inertia needs accelerating motion: torque steps or changes");
  return fmt::format("{}", fmt::join(advice, "; "));
}

}  // namespace

bool IsTorqueStepLog(const AxisLog& log) {
  if (log.force.size() < 2) return false;
  std::size_t changes = 0;
  for (std::size_t k = 1; k < log.force.size(); ++k) changes += log.force[k] != log.force[k - 1];
  return static_cast<double>(changes) < 0.02 * static_cast<double>(log.force.size());
}

double CalcLoggedStartRate(const std::vector<double>& time, const std::vector<double>& position,
                           const std::vector<double>& rate) {
  if (!rate.empty()) return rate.front();
  if (time.size() < 2) return 0.0;
  const std::size_t m = std::min(kStartRateSamples, time.size() - 1);
  return (position[m] - position[0]) / (time[m] - time[0]);
}

AxisStart AxisLogStart(const AxisLog& log) {
  if (std::isfinite(log.start_rate)) return {log.position.front(), log.start_rate};
  return {log.position.front(), CalcLoggedStartRate(log.time, log.position, log.rate)};
}

namespace {

// The free terms (start values from `initial` where given, at least their
// bound), their indices, and every term's value for the fixed part.
struct OeDesign {
  AxisParameters fixed;
  std::vector<int> terms;
  std::vector<FitParameter> parameters;
};

// Parameter j is a nonlinear term's scale (models/axis_term.h scale_row).
bool IsScale(std::size_t j) {
  const AxisTermParameter& owner = AxisParameterTerm(j);
  return owner.term->scale_row() >= 0 && owner.row == static_cast<std::size_t>(owner.term->scale_row());
}

OeDesign MakeOeDesign(const AxisSection& start, const AxisParameters* initial, const std::vector<std::string>& free) {
  OeDesign d;
  std::vector<bool> free_index(AxisParameterCount(), false);
  for (const auto& term : ResolveAxisTerms(start, free)) {
    double value = term.value;
    const auto& row = AxisTermRow(term.index);
    if (term.free && initial != nullptr && term.index < AxisLinearCount()) value = ModelValue(row, *initial);
    const double lower = row.spec.lower_bound;
    if (term.free) {
      value = std::max(value, lower);
      free_index[term.index] = true;
      if (term.index == AxisIndex(&AxisParameters::inertia)) {
        if (!(value > 0.0)) {
          throw InputError("‹method› oe: the inertia needs a start value > 0 (axis.inertia in ‹params›)");
        }
        d.parameters.push_back({term.key, value, 1e-6 * value, 0.0});
      } else if (IsScale(term.index)) {
        d.parameters.push_back({term.key, value, 1e-6 * std::max(value, 1e-9), 0.0});
      } else {
        double scale = std::abs(value);
        if (scale == 0.0) scale = 1e-3;  // refined by the solver; friction scales of real axes
        d.parameters.push_back({term.key, value, lower, scale});
      }
      d.terms.push_back(static_cast<int>(term.index));
    }
    ModelValue(row, d.fixed) = value;
  }
  // Each nonlinear term checks its own start (models/axis_term.h).
  const AxisValues values = AxisValuesOf(d.fixed);
  for (const AxisTerm* term : AxisTerms()) {
    if (term->linear()) continue;
    const std::size_t first = AxisFirstIndex(*term), n = term->Rows().size();
    term->CheckFitStart(&values[first], std::vector<bool>(free_index.begin() + static_cast<std::ptrdiff_t>(first),
                                                          free_index.begin() + static_cast<std::ptrdiff_t>(first + n)));
  }
  if (!(d.fixed.inertia > 0.0)) {
    throw InputError("‹method› oe: the axis needs an inertia > 0: give axis.inertia or free it");
  }
  return d;
}

// Each log's start, channel weights (1 / RMS deviation) and weighted
// measurements; the integrator's tolerance scales over all logs.
struct OeLogs {
  std::vector<OeLog> logs;
  double position_range = 0.0, rate_range = 0.0;
};

OeLogs PrepareOeLogs(const std::vector<AxisLog>& logs) {
  OeLogs out;
  out.logs.resize(logs.size());
  for (std::size_t i = 0; i < logs.size(); ++i) {
    const AxisLog& log = logs[i];
    if (log.time.size() < kMinAxisLogSamples) {
      throw InputError(fmt::format("{}: {} samples: the axis fit needs at least {}", log.path, log.time.size(),
                                   kMinAxisLogSamples));
    }
    OeLog& l = out.logs[i];
    l.log = &log;
    const AxisStart log_start = AxisLogStart(log);
    l.q0 = log_start.position;
    l.v0 = log_start.rate;
    const double q_scale = CalcRmsDeviation(log.position);
    if (!(q_scale > 0.0)) {
      throw IdentificationError(fmt::format("{}: the position never changes: output error has nothing to fit",
                                            log.path));
    }
    l.position_weight = 1.0 / q_scale;
    out.position_range = std::max(out.position_range, q_scale);
    if (!log.rate.empty()) {
      const double v_scale = CalcRmsDeviation(log.rate);
      if (v_scale > 0.0) l.rate_weight = 1.0 / v_scale;
      out.rate_range = std::max(out.rate_range, v_scale);
    }
    for (std::size_t k = 0; k < log.time.size(); ++k) {
      if (!log.measured.empty() && !log.measured[k]) continue;
      l.rows.push_back(k);
      l.weighted_position.push_back(log.position[k] * l.position_weight);
      if (!log.rate.empty()) l.weighted_rate.push_back(log.rate[k] * l.rate_weight);
    }
    const double duration = log.time.back() - log.time.front();
    out.rate_range = std::max(out.rate_range, q_scale / std::max(duration, 1e-9));
  }
  return out;
}

// A nonlinear term's scale parameter (models/axis_term.h scale_row) has a
// plateau (a fading excess whose scale grows without bound joins a linear
// term) that attracts the solver from poor linear terms: with it free, the
// linear terms are fitted first with the nonlinear ones held at their
// start, then all from there, starting the scale also at a quarter and
// four times its value; the lowest cost wins.
FitResult FitFromPlateau(OeLogs& prepared, const OeDesign& d, AxisOeResiduals& residuals,
                         const std::vector<FitChannel>& channels, const FitOptions& fit_options, std::size_t vs) {
  std::vector<FitParameter> parameters = d.parameters;
  std::vector<int> linear_terms;
  std::vector<FitParameter> linear_parameters;
  for (std::size_t j = 0; j < d.terms.size(); ++j) {
    if (d.terms[j] < static_cast<int>(AxisLinearCount())) {
      linear_terms.push_back(d.terms[j]);
      linear_parameters.push_back(parameters[j]);
    }
  }
  if (!linear_terms.empty()) {
    AxisOeResiduals stage(prepared.logs, d.fixed, linear_terms, 1e-8 * prepared.position_range,
                          1e-8 * prepared.rate_range);
    FitOptions quiet = fit_options;
    quiet.identifiability_threshold = 0.0;  // judged on the full fit
    try {
      const FitResult first = FitLeastSquares(stage, linear_parameters, channels, quiet);
      for (std::size_t j = 0, m = 0; j < d.terms.size(); ++j) {
        if (d.terms[j] < static_cast<int>(AxisLinearCount())) parameters[j].initial = first.estimates[m++].value;
      }
    } catch (const IdentificationError&) {
      // The full fit from the given start reports what is wrong.
    }
  }
  std::optional<FitResult> best;
  std::string first_failure;
  std::vector<std::string> first_parameters;
  for (double factor : {1.0, 0.25, 4.0}) {
    std::vector<FitParameter> from = parameters;
    from[vs].initial *= factor;
    try {
      FitResult fit = FitLeastSquares(residuals, from, channels, fit_options);
      if (!best || fit.cost < best->cost) best = std::move(fit);
    } catch (const IdentificationError& e) {
      if (first_failure.empty()) {
        first_failure = e.what();
        first_parameters = e.parameters();
      }
    }
  }
  if (!best) throw IdentificationError(first_failure, first_parameters);
  return std::move(*best);
}

}  // namespace

std::vector<std::vector<double>> SimulateAxisLogRates(const std::vector<AxisLog>& logs, const AxisParameters& params) {
  std::vector<std::vector<double>> out(logs.size());
  for (std::size_t i = 0; i < logs.size(); ++i) {
    const AxisLog& log = logs[i];
    if (log.time.size() < 2 || !(params.inertia > 0.0)) continue;
    // The output-error fit's tolerances (PrepareOeLogs): 1e-8 of the log's spread.
    const double q_scale = std::max(CalcRmsDeviation(log.position), 1e-12);
    const double duration = std::max(log.time.back() - log.time.front(), 1e-9);
    const double v_scale = std::max(log.rate.empty() ? 0.0 : CalcRmsDeviation(log.rate), q_scale / duration);
    const AxisStart start = AxisLogStart(log);
    AxisSimulator simulator({}, 1e-8 * q_scale, 1e-8 * v_scale);
    AxisResponse response;
    try {
      simulator.Simulate(params, log.time, log.force, start.position, start.rate, false, &response);
    } catch (const IdentificationError&) {
      continue;
    }
    out[i] = std::move(response.rate);
  }
  return out;
}

AxisOeOutput FitAxisOutputError(const std::vector<AxisLog>& logs, const AxisSection& start,
                                const AxisParameters* initial, const AxisOeOptions& options) {
  RequireValid(options);
  if (logs.empty()) throw OptionError("no logs given");
  CheckFreeNames(AxisParameterTable(), "axis", options.free);
  const OeDesign d = MakeOeDesign(start, initial, options.free);
  OeLogs prepared = PrepareOeLogs(logs);
  std::vector<OeLog>& oe = prepared.logs;
  AxisOeResiduals residuals(oe, d.fixed, d.terms, 1e-8 * prepared.position_range, 1e-8 * prepared.rate_range);
  std::vector<FitChannel> channels;
  for (const auto& l : oe) {
    const int n = static_cast<int>(l.rows.size());
    channels.push_back({l.log->path + ":q", l.first_row, n, l.weighted_position.data()});
    if (l.rate_weight > 0.0) channels.push_back({l.log->path + ":qd", l.first_row + n, n, l.weighted_rate.data()});
  }
  FitOptions fit_options = options.fit;
  if (!fit_options.advice) fit_options.advice = OeAdvice;
  AxisOeOutput out;
  const auto vs = std::find_if(d.terms.begin(), d.terms.end(), [](int j) { return IsScale(static_cast<std::size_t>(j)); });
  out.fit = vs == d.terms.end() ? FitLeastSquares(residuals, d.parameters, channels, fit_options)
                                : FitFromPlateau(prepared, d, residuals, channels, fit_options,
                                                 static_cast<std::size_t>(vs - d.terms.begin()));
  DecideAxisDetermined(out.fit, kMaxRelativeStd, -1.0);
  // RMSE back in the channels' units (fit % and lag-1 do not depend on the weight).
  for (std::size_t c = 0, i = 0; i < oe.size(); ++i) {
    out.fit.channels[c++].rmse /= oe[i].position_weight;
    if (oe[i].rate_weight > 0.0) out.fit.channels[c++].rmse /= oe[i].rate_weight;
  }
  std::vector<double> estimate;
  for (const auto& e : out.fit.estimates) estimate.push_back(e.value);
  out.params = d.fixed;
  for (std::size_t j = 0; j < d.terms.size(); ++j) ModelValue(AxisTermRow(static_cast<std::size_t>(d.terms[j])), out.params) = estimate[j];
  out.position.resize(oe.size());
  out.rate.resize(oe.size());
  for (std::size_t i = 0; i < oe.size(); ++i) residuals.Simulate(estimate.data(), i, &out.position[i], &out.rate[i]);
  out.start_from = initial != nullptr ? "IDIM-LS estimates" : "the parameter file";
  if (options.per_log && logs.size() > 1) {
    AxisOeOptions alone = options;
    alone.per_log = false;
    AddPerLogFits(out.fit, LogLabels(logs),
                  [&](std::size_t i) { return FitAxisOutputError({logs[i]}, start, initial, alone).fit.estimates; });
  }
  return out;
}

}  // namespace driveid
