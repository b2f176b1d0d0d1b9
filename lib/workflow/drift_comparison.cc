#include "workflow/drift_comparison.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/errors.h"

namespace driveid {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const ParameterEstimate* Find(const std::vector<ParameterEstimate>& estimates, const std::string& name) {
  for (const auto& e : estimates) {
    if (e.name == name) return &e;
  }
  return nullptr;
}

bool Exceeds(const ParameterChange& c, const DriftGate& gate) {
  if (!gate.max_percent && !gate.max_z) return false;
  const bool percent = !gate.max_percent || (std::isfinite(c.relative_change) &&
                                             std::abs(100.0 * c.relative_change) > *gate.max_percent);
  const bool z = !gate.max_z || (std::isfinite(c.z) && std::abs(c.z) > *gate.max_z);
  return percent && z;
}

}  // namespace

FileComparison CompareEstimates(const std::string& file, const std::vector<ParameterEstimate>& base,
                                const std::vector<ParameterEstimate>& other, const DriftGate& gate) {
  std::vector<std::string> unknown;
  for (const auto& name : gate.parameters) {
    if (!Find(base, name)) unknown.push_back(name);
  }
  if (!unknown.empty()) {
    std::vector<std::string> known;
    for (const auto& e : base) known.push_back(e.name);
    throw InputError(fmt::format("‹parameters›: the base has no estimate of {} (it has {})", fmt::join(unknown, ", "),
                                 fmt::join(known, ", ")));
  }
  FileComparison out;
  out.file = file;
  for (const auto& b : base) {
    if (!gate.parameters.empty() &&
        std::find(gate.parameters.begin(), gate.parameters.end(), b.name) == gate.parameters.end()) {
      continue;
    }
    const bool gated = gate.max_percent || gate.max_z;
    const ParameterEstimate* e = Find(other, b.name);
    if (e == nullptr) {
      out.missing.push_back(b.name);
      if (gated) out.undecided.push_back(fmt::format("{}: the file has no estimate of it", b.name));
      continue;
    }
    ParameterChange c;
    c.name = b.name;
    c.base = b.value;
    c.base_std = b.standard_error;
    c.value = e->value;
    c.value_std = e->standard_error;
    c.relative_change = b.value != 0.0 ? (e->value - b.value) / std::abs(b.value) : kNaN;
    const double s = std::hypot(b.standard_error, e->standard_error);
    c.z = s > 0.0 ? (e->value - b.value) / s : kNaN;
    c.drift = Exceeds(c, gate);
    if (gate.max_percent && !std::isfinite(c.relative_change)) {
      out.undecided.push_back(fmt::format("{}: the base value is 0, so a change in percent is undefined", b.name));
    }
    if (gate.max_z && !std::isfinite(c.z)) {
      out.undecided.push_back(fmt::format("{}: neither file gives it a std, so z is undefined", b.name));
    }
    out.drift = out.drift || c.drift;
    out.parameters.push_back(c);
  }
  return out;
}

}  // namespace driveid
