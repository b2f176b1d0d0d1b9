#include "report/fit_summary.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/estimate_record.h"
#include "core/fit_section.h"

namespace driveid {

std::string FitPercentText(double fit_percent, double variation) {
  if (!std::isnan(fit_percent)) return fmt::format("{:.2f} %", fit_percent);
  return variation > 0.0 ? fmt::format("n/a (nearly constant: std {:.2g} % of its RMS)", 100.0 * variation)
                         : "n/a (constant)";
}

namespace {

// NaN (no fit %: a constant channel) sorts above every fit %.
double FitPercentOrder(const ChannelStatistics& c) { return std::isnan(c.fit_percent) ? HUGE_VAL : c.fit_percent; }

// A line per channel; beyond kListedChannels the ranges over all channels
// and the channels of the lowest fit and the most correlated residuals.
std::string FormatChannelLines(const std::vector<ChannelStatistics>& channels) {
  // R^2 = 1 - SSR/SST = 1 - (1 - fit/100)^2 (SysId reports R^2 and RMSE per test).
  const auto line = [](const ChannelStatistics& c) {
    const double unexplained = 1.0 - c.fit_percent / 100.0;
    return fmt::format("{}: {} samples, rmse {:.4g}, fit {}{}, residual lag-1 autocorrelation {:.3f}, std x {:.2f} "
                       "for it ({} lags)\n",
                       c.name, c.samples, c.rmse, FitPercentText(c.fit_percent, c.variation),
                       std::isnan(c.fit_percent) ? std::string() : fmt::format(" (R^2 {:.4f})", 1.0 - unexplained * unexplained),
                       c.autocorrelation, c.inflation, c.bandwidth);
  };
  std::string out;
  if (channels.size() <= kListedChannels) {
    for (const auto& c : channels) out += line(c);
    return out;
  }
  const auto range = [&](double ChannelStatistics::*member) {
    const auto [low, high] = std::minmax_element(channels.begin(), channels.end(),
                                                 [&](const auto& a, const auto& b) { return a.*member < b.*member; });
    return std::pair{(*low).*member, (*high).*member};
  };
  double fit_low = HUGE_VAL, fit_high = -HUGE_VAL;
  for (const auto& c : channels) {
    if (std::isnan(c.fit_percent)) continue;
    fit_low = std::min(fit_low, c.fit_percent);
    fit_high = std::max(fit_high, c.fit_percent);
  }
  const auto [rmse_low, rmse_high] = range(&ChannelStatistics::rmse);
  const auto [lag_low, lag_high] = range(&ChannelStatistics::autocorrelation);
  const auto [inflation_low, inflation_high] = range(&ChannelStatistics::inflation);
  const std::string fit_range =
      fit_low <= fit_high ? fmt::format("{:.2f} to {:.2f} %", fit_low, fit_high) : std::string("n/a (constant)");
  out += fmt::format("{} channels (each in the parameter file and ‹json›): fit {}, rmse {:.4g} to "
                     "{:.4g}, residual lag-1 {:.3f} to {:.3f}, std x {:.2f} to {:.2f}\n",
                     channels.size(), fit_range, rmse_low, rmse_high, lag_low, lag_high, inflation_low,
                     inflation_high);
  const auto worst_fit = std::min_element(channels.begin(), channels.end(),
                                          [](const auto& a, const auto& b) { return FitPercentOrder(a) < FitPercentOrder(b); });
  const auto most_correlated = std::max_element(
      channels.begin(), channels.end(), [](const auto& a, const auto& b) { return a.autocorrelation < b.autocorrelation; });
  out += "  lowest fit: " + line(*worst_fit);
  out += "  most correlated residuals: " + line(*most_correlated);
  return out;
}

}  // namespace

std::string FormatFitTable(const FitResult& fit, const FitProvenance& provenance) {
  std::string out;
  const bool units = std::any_of(fit.estimates.begin(), fit.estimates.end(), [](const auto& e) { return !e.unit.empty(); });
  out += fmt::format("{:<14} {:>14} {:>12} {:>9}   {:<27}{}\n", "parameter", "estimate", "std", "rel.std", "95 % interval",
                     units ? " unit" : "");
  for (const auto& e : fit.estimates) {
    // At zero (e.g. a friction stuck at its bound) a relative std means nothing.
    const std::string relative =
        e.value != 0.0 ? fmt::format("{:>8.3f}%", 100.0 * e.standard_error / std::abs(e.value)) : fmt::format("{:>9}", "-");
    const std::string interval = fmt::format("[{:.6g}, {:.6g}]", e.ci95_low, e.ci95_high);
    out += units ? fmt::format("{:<14} {:>14.6g} {:>12.3g} {}   {:<27} {}\n", e.name, e.value, e.standard_error,
                               relative, interval, e.unit)
                 : fmt::format("{:<14} {:>14.6g} {:>12.3g} {}   {}\n", e.name, e.value, e.standard_error, relative,
                               interval);
  }
  out += "\n";
  out += FormatChannelLines(fit.channels);
  const std::size_t p = fit.estimates.size();
  if (p > kFullCorrelationParameters) {
    out += fmt::format("correlation: {} parameters, the 10 strongest pairs (all: ‹json›):\n", p);
    for (const auto& pair : StrongestCorrelations(fit, 10)) {
      out += fmt::format("  {:<14} {:<14} {:>7.3f}\n", fit.estimates[pair.first].name, fit.estimates[pair.second].name,
                         pair.correlation);
    }
  } else if (p > 1) {
    out += "correlation:\n";
    for (std::size_t i = 0; i < p; ++i) {
      out += fmt::format("  {:<14}", fit.estimates[i].name);
      for (std::size_t j = 0; j <= i; ++j) out += fmt::format(" {:>7.3f}", fit.correlation[i * p + j]);
      out += "\n";
    }
  }
  const std::vector<double>& singular = fit.singular_values;
  if (singular.size() > 12) {
    out += fmt::format("identifiability: singular values of the normalised Jacobian [{:.3g}, ..., {:.3g}] ({} of them)\n",
                       fmt::join(singular.begin(), singular.begin() + 6, ", "),
                       fmt::join(singular.end() - 6, singular.end(), ", "), singular.size());
  } else {
    out += fmt::format("identifiability: singular values of the normalised Jacobian [{:.3g}]\n",
                       fmt::join(singular, ", "));
  }
  out += fmt::format("solver: {} after {} iterations ({}); model {}\n", fit.converged ? "converged" : "NOT converged",
                     fit.iterations, fit.termination, provenance.model.empty() ? "-" : provenance.model);
  out += FormatPerLogTable(fit);
  if (!fit.validation.empty()) out += FormatValidationTable(fit.validation);
  for (const auto& note : fit.notes) out += "note: " + note + "\n";
  if (!fit.warnings.empty()) {
    out += fmt::format("adequacy (docs/models.md#adequacy): {} warning{}\n", fit.warnings.size(),
                       fit.warnings.size() > 1 ? "s" : "");
    for (const auto& w : fit.warnings) out += "  " + w + "\n";
  } else {
    out += "adequacy (docs/models.md#adequacy): no warnings\n";
  }
  return out;
}

namespace {

// A failure's first line with every number blanked: logs that failed for the
// same reason (each SysId test moves one way only) compare equal.
std::string FailureKind(const std::string& failure) {
  std::string out;
  bool in_number = false;
  for (const char c : failure.substr(0, failure.find('\n'))) {
    const bool digit = c >= '0' && c <= '9';
    if (digit || (in_number && (c == '.' || c == 'e' || c == '-' || c == '+'))) {
      if (!in_number) out += '#';
      in_number = true;
    } else {
      in_number = false;
      out += c;
    }
  }
  return out;
}

std::string FormatEstimateSets(const std::vector<EstimateSet>& sets) {
  std::string out;
  // Several sets that all failed alike: one line, not one per log.
  const bool alike = sets.size() > 1 && std::all_of(sets.begin(), sets.end(), [&](const EstimateSet& set) {
    return !set.failure.empty() && FailureKind(set.failure) == FailureKind(sets.front().failure);
  });
  if (alike) {
    const std::string& first = sets.front().failure;
    return fmt::format("  none of the {} fits alone succeeded, each for the same reason: {}\n", sets.size(),
                       first.substr(0, first.find('\n')));
  }
  for (const auto& log : sets) {
    out += fmt::format("  {}\n", log.label);
    if (!log.failure.empty()) {
      out += fmt::format("    not fitted: {}\n", log.failure.substr(0, log.failure.find('\n')));
      continue;
    }
    for (const auto& e : log.estimates) {
      out += fmt::format("    {:<14} {:>14.6g} +- {:.3g}\n", e.name, e.value, e.standard_error);
    }
  }
  return out;
}

Json EstimateSetsJson(const std::vector<EstimateSet>& sets) {
  Json out = Json::array();
  for (const auto& set : sets) {
    Json entry = {{"label", set.label}};
    if (!set.failure.empty()) entry["failure"] = set.failure;
    entry["estimates"] = Json::object();
    for (const auto& e : set.estimates) entry["estimates"][e.name] = {{"value", e.value}, {"std", e.standard_error}};
    out.push_back(entry);
  }
  return out;
}

}  // namespace

std::string FormatValidationTable(const std::vector<ChannelStatistics>& logs) {
  std::string out = fmt::format("{:<40} {:>8} {:>12} {:>8} {:>10} {:>8}\n", "validation: log", "samples", "rmse",
                                "fit %", "rel. err %", "lag-1");
  for (const auto& c : logs) {
    const std::string fit = std::isnan(c.fit_percent) ? "n/a" : fmt::format("{:.2f}", c.fit_percent);
    const std::string relative =
        std::isnan(c.relative_error_percent) ? "n/a" : fmt::format("{:.2f}", c.relative_error_percent);
    out += fmt::format("{:<40} {:>8} {:>12.4g} {:>8} {:>10} {:>8.3f}\n", c.name, c.samples, c.rmse, fit, relative,
                       c.autocorrelation);
  }
  return out;
}

Json ValidationJson(const std::vector<ChannelStatistics>& logs) {
  Json out = Json::array();
  for (const auto& c : logs) {
    out.push_back({{"log", c.name},
                   {"samples", c.samples},
                   {"rmse", c.rmse},
                   {"fit_percent", c.fit_percent},
                   {"relative_error_percent", c.relative_error_percent},
                   {"autocorrelation", c.autocorrelation}});
  }
  return out;
}

std::string FormatPerLogTable(const FitResult& fit) {
  std::string out;
  if (!fit.sensitivity.empty()) out += "processing sensitivity (the same fit at other cutoffs):\n" + FormatEstimateSets(fit.sensitivity);
  if (fit.per_log.empty()) return out;
  out += "per log (each fitted alone):\n" + FormatEstimateSets(fit.per_log);
  for (const auto& t : fit.heterogeneity) {
    out += fmt::format("  {:<14} Cochran Q {:.3g} on {} dof, p = {:.2g}, I^2 = {:.0f} %\n", t.parameter, t.q, t.dof,
                       t.p_value, 100.0 * t.i_squared);
  }
  return out;
}

namespace {

// One key of the fit section (core/fit_section.h) as the JSON summary has
// it: the correlation always as the full matrix; the derived quantities are
// the parameter file's only (null here, left out).
Json FitKeyJson(FitKey key, const FitResult& fit, const FitProvenance& provenance) {
  Json out;
  switch (key) {
    case FitKey::kCommand: return provenance.command;
    case FitKey::kVersion: return provenance.version;
    case FitKey::kModel: return provenance.model;
    case FitKey::kData:
      out = Json::array();
      for (const auto& d : provenance.data) {
        Json record = {{"file", d.file}, {"sha256", d.sha256}, {"samples", d.samples}};
        if (!d.segment.empty()) record["segment"] = d.segment;
        if (!d.notes.empty()) record["notes"] = d.notes;
        out.push_back(record);
      }
      return out;
    case FitKey::kEstimates:
      out = Json::object();
      for (const auto& e : fit.estimates) {
        struct JsonRecordWriter {
          Json record = Json::object();
          void Scalar(const char* key, EstimateField, const double& v) { record[key] = v; }
          void Interval(const char* key, const double& low, const double& high) { record[key] = {low, high}; }
        } writer;
        VisitEstimateRecord(writer, e);
        out[e.name] = std::move(writer.record);
        if (!e.unit.empty()) out[e.name]["unit"] = e.unit;
      }
      return out;
    case FitKey::kDerived: return nullptr;
    case FitKey::kCorrelation: {
      const std::size_t p = fit.estimates.size();
      out = Json::array();
      for (std::size_t i = 0; i < p; ++i) {
        Json row = Json::array();
        for (std::size_t j = 0; j < p; ++j) row.push_back(fit.correlation[i * p + j]);
        out.push_back(row);
      }
      return out;
    }
    case FitKey::kRmse:
    case FitKey::kFitPercent:
    case FitKey::kAutocorrelation:
    case FitKey::kInflation:
      out = Json::object();
      for (const auto& c : fit.channels) {
        out[c.name] = key == FitKey::kRmse         ? c.rmse
                      : key == FitKey::kFitPercent ? c.fit_percent
                      : key == FitKey::kAutocorrelation ? c.autocorrelation
                                                        : c.inflation;
      }
      return out;
    case FitKey::kSingularValues: return fit.singular_values;
    case FitKey::kIterations: return fit.iterations;
    case FitKey::kConverged: return fit.converged;
  }
  return out;
}

}  // namespace

Json FitJson(const FitResult& fit, const FitProvenance& provenance) {
  Json out;
  for (const FitKey key : kFitSectionKeys) {
    Json value = FitKeyJson(key, fit, provenance);
    if (!value.is_null()) out[FitKeyName(key)] = std::move(value);
  }
  out["warnings"] = fit.warnings;
  out["notes"] = fit.notes;
  if (!fit.validation.empty()) out["validation"] = ValidationJson(fit.validation);
  if (!fit.sensitivity.empty()) out["sensitivity"] = EstimateSetsJson(fit.sensitivity);
  if (!fit.per_log.empty()) {
    out["per_log"] = EstimateSetsJson(fit.per_log);
    out["heterogeneity"] = Json::object();
    for (const auto& t : fit.heterogeneity) {
      out["heterogeneity"][t.parameter] = {{"q", t.q}, {"dof", t.dof}, {"p", t.p_value}, {"i_squared", t.i_squared}};
    }
  }
  return out;
}

}  // namespace driveid
