#include "report/joint_report.h"

#include <cmath>
#include <optional>

#include <fmt/format.h>

namespace driveid {
namespace {

struct Derived {
  const char* key;
  double value;
  const char* unit;
  const char* description;
};

std::optional<std::vector<Derived>> JointDerived(const ParameterFile& file) {
  const JointSection* s = file.Find<JointSection>();
  if (!s || !(s->motor_inertia.value_or(0.0) > 0.0) || !(s->link_inertia.value_or(0.0) > 0.0) ||
      !(s->stiffness.value_or(0.0) > 0.0)) {
    return std::nullopt;
  }
  const double jm = *s->motor_inertia, jl = *s->link_inertia, k = *s->stiffness, d = s->damping.value_or(0.0);
  const double wr = std::sqrt(k * (1.0 / jm + 1.0 / jl)), wa = std::sqrt(k / jl);
  return std::vector<Derived>{
      {"resonance_hz", wr / (2.0 * M_PI), "Hz", "sqrt(k (1/J_m + 1/J_l)) / 2 pi"},
      {"antiresonance_hz", wa / (2.0 * M_PI), "Hz", "motor side, sqrt(k / J_l) / 2 pi"},
      {"damping_ratio", d * wr / (2.0 * k), "", "of the relative mode, d w_r / (2 k)"},
      {"inertia_ratio", jl / jm, "", "J_l / J_m"},
      {"total_inertia", jm + jl, "kg m^2", "J_m + J_l, link side"},
  };
}

}  // namespace

std::string FormatJointReport(const ParameterFile& file) {
  std::string out;
  if (const JointSection* s = file.Find<JointSection>()) {
    out += "elastic joint (docs/models.md#elastic-joint), link side:\n";
    for (const auto& row : JointParameterTable()) {
      const std::optional<double>& v = (*s).*(row.in_section);
      if (!v) continue;
      std::string std_text;
      for (const auto& e : file.fit_estimates) {
        if (e.name == row.spec.key) std_text = fmt::format("+- {:.3g}", e.standard_error);
      }
      out += fmt::format("  {:<20} {:>14.6g} {:<12} {}\n", row.spec.key, *v, std_text, row.spec.unit);
    }
    if (const auto derived = JointDerived(file)) {
      for (const auto& d : *derived) out += fmt::format("  {:<20} {:>14.6g} {:<12} {} ({})\n", d.key, d.value, "", d.unit, d.description);
    }
  }
  if (const FrequencyResponseSection* f = file.Find<FrequencyResponseSection>()) {
    out += "frequency response (docs/models.md#frequency-response), measured:\n";
    if (f->resonance_hz) out += fmt::format("  resonance      {:>10.6g} +- {:.3g} Hz\n", *f->resonance_hz, f->resonance_hz_std.value_or(0.0));
    if (f->antiresonance_hz) {
      out += fmt::format("  anti-resonance {:>10.6g} +- {:.3g} Hz\n", *f->antiresonance_hz, f->antiresonance_hz_std.value_or(0.0));
    }
    if (f->band_hz) out += fmt::format("  band           [{:.4g}, {:.4g}] Hz\n", (*f->band_hz)[0], (*f->band_hz)[1]);
    if (f->method) out += fmt::format("  method         {}\n", *f->method);
  }
  return out;
}

Json JointReportJson(const ParameterFile& file) {
  Json out = Json::object();
  if (const JointSection* s = file.Find<JointSection>()) {
    Json joint = Json::object();
    for (const auto& row : JointParameterTable()) {
      const std::optional<double>& v = (*s).*(row.in_section);
      if (v) joint[row.spec.key] = *v;
    }
    if (const auto derived = JointDerived(file)) {
      for (const auto& d : *derived) joint["derived"][d.key] = d.value;
    }
    out["joint"] = joint;
  }
  if (const FrequencyResponseSection* f = file.Find<FrequencyResponseSection>()) {
    Json frf = Json::object();
    if (f->resonance_hz) frf["resonance_hz"] = {{"value", *f->resonance_hz}, {"std", f->resonance_hz_std.value_or(0.0)}};
    if (f->antiresonance_hz) {
      frf["antiresonance_hz"] = {{"value", *f->antiresonance_hz}, {"std", f->antiresonance_hz_std.value_or(0.0)}};
    }
    if (f->band_hz) frf["band_hz"] = {(*f->band_hz)[0], (*f->band_hz)[1]};
    if (f->method) frf["method"] = *f->method;
    out["frf"] = frf;
  }
  return out;
}

}  // namespace driveid
