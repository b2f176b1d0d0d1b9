#include "report/fit_summary.h"

#include <cmath>

#include <fmt/format.h>

namespace driveid {

std::string JsonString(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    const unsigned char u = static_cast<unsigned char>(c);
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (u < 0x20) out += fmt::format("\\u{:04x}", u);
        else out += c;
    }
  }
  return out + "\"";
}

std::string JsonNumber(double value) { return std::isfinite(value) ? fmt::format("{}", value) : "null"; }

std::string FormatFitTable(const FitResult& fit, const FitProvenance& provenance) {
  std::string out;
  out += fmt::format("{:<14} {:>14} {:>12} {:>9}   {:<27}\n", "parameter", "estimate", "std", "rel.std", "95 % interval");
  for (const auto& e : fit.estimates) {
    const double relative = e.value != 0.0 ? 100.0 * e.standard_error / std::abs(e.value) : 0.0;
    out += fmt::format("{:<14} {:>14.6g} {:>12.3g} {:>8.3f}%   [{:.6g}, {:.6g}]\n", e.name, e.value,
                       e.standard_error, relative, e.ci95_low, e.ci95_high);
  }
  out += "\n";
  for (const auto& c : fit.channels) {
    out += fmt::format("{}: {} samples, rmse {:.4g}, fit {:.2f} %\n", c.name, c.samples, c.rmse, c.fit_percent);
  }
  const std::size_t p = fit.estimates.size();
  if (p > 1) {
    out += "correlation:\n";
    for (std::size_t i = 0; i < p; ++i) {
      out += fmt::format("  {:<14}", fit.estimates[i].name);
      for (std::size_t j = 0; j <= i; ++j) out += fmt::format(" {:>7.3f}", fit.correlation[i * p + j]);
      out += "\n";
    }
  }
  out += fmt::format("identifiability: singular values of the normalised Jacobian [{:.3g}]\n",
                     fmt::join(fit.singular_values, ", "));
  out += fmt::format("solver: {} after {} iterations ({}); model {}\n", fit.converged ? "converged" : "NOT converged",
                     fit.iterations, fit.termination, provenance.model.empty() ? "-" : provenance.model);
  return out;
}

std::string FormatFitJson(const FitResult& fit, const FitProvenance& provenance) {
  std::string out = "{";
  out += fmt::format("\"command\":{},\"version\":{},\"model\":{},", JsonString(provenance.command),
                     JsonString(provenance.version), JsonString(provenance.model));
  out += "\"data\":[";
  for (std::size_t i = 0; i < provenance.data.size(); ++i) {
    const auto& d = provenance.data[i];
    out += fmt::format("{}{{\"file\":{},\"sha256\":\"{}\",\"samples\":{}}}", i ? "," : "", JsonString(d.file), d.sha256,
                       d.samples);
  }
  out += "],\"estimates\":{";
  for (std::size_t i = 0; i < fit.estimates.size(); ++i) {
    const auto& e = fit.estimates[i];
    out += fmt::format("{}{}:{{\"value\":{},\"std\":{},\"ci95\":[{},{}]}}", i ? "," : "", JsonString(e.name),
                       JsonNumber(e.value), JsonNumber(e.standard_error), JsonNumber(e.ci95_low),
                       JsonNumber(e.ci95_high));
  }
  out += "},\"correlation\":[";
  const std::size_t p = fit.estimates.size();
  for (std::size_t i = 0; i < p; ++i) {
    out += i ? ",[" : "[";
    for (std::size_t j = 0; j < p; ++j) out += (j ? "," : "") + JsonNumber(fit.correlation[i * p + j]);
    out += "]";
  }
  out += "],\"rmse\":{";
  for (std::size_t i = 0; i < fit.channels.size(); ++i) {
    out += fmt::format("{}{}:{}", i ? "," : "", JsonString(fit.channels[i].name), JsonNumber(fit.channels[i].rmse));
  }
  out += "},\"fit_percent\":{";
  for (std::size_t i = 0; i < fit.channels.size(); ++i) {
    out += fmt::format("{}{}:{}", i ? "," : "", JsonString(fit.channels[i].name),
                       JsonNumber(fit.channels[i].fit_percent));
  }
  out += "},\"singular_values\":[";
  for (std::size_t i = 0; i < fit.singular_values.size(); ++i) out += (i ? "," : "") + JsonNumber(fit.singular_values[i]);
  out += fmt::format("],\"iterations\":{},\"converged\":{}}}\n", fit.iterations, fit.converged ? "true" : "false");
  return out;
}

}  // namespace driveid
