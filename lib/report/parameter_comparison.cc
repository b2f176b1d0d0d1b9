#include "report/parameter_comparison.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace driveid {
namespace {

Json Number(double value) { return std::isfinite(value) ? Json(value) : Json(nullptr); }

std::string GateText(const DriftGate& gate) {
  std::vector<std::string> parts;
  if (gate.max_percent) parts.push_back(fmt::format("|change| > {:g} %", *gate.max_percent));
  if (gate.max_z) parts.push_back(fmt::format("|z| > {:g}", *gate.max_z));
  return parts.empty() ? "no drift gate" : fmt::format("drift: {}", fmt::join(parts, " and "));
}

}  // namespace

std::string FormatComparisons(const std::string& base_file, const std::vector<FileComparison>& files,
                              const DriftGate& gate) {
  std::string out = fmt::format("compared with {} ({})\n", base_file, GateText(gate));
  std::size_t drifted = 0;
  for (const auto& f : files) {
    drifted += f.drift ? 1 : 0;
    out += fmt::format("{}{}\n", f.file, f.drift ? ": DRIFT" : "");
    for (const auto& c : f.parameters) {
      out += fmt::format("  {:<18} {:>12.6g} -> {:<12.6g} {:>+9.3g} %   z {:>+8.3g}{}\n", c.name, c.base, c.value,
                         100.0 * c.relative_change, c.z, c.drift ? "   drift" : "");
    }
    if (!f.missing.empty()) out += fmt::format("  no estimate of {}\n", fmt::join(f.missing, ", "));
    for (const auto& u : f.undecided) out += fmt::format("  the gate cannot judge {}\n", u);
  }
  out += fmt::format("{} of {} files drifted\n", drifted, files.size());
  return out;
}

Json ComparisonsJson(const std::string& base_file, const std::vector<FileComparison>& files, const DriftGate& gate) {
  Json out = Json::object();
  out["base"] = base_file;
  out["gate"] = {{"fail_above_percent", gate.max_percent ? Json(*gate.max_percent) : Json(nullptr)},
                 {"z", gate.max_z ? Json(*gate.max_z) : Json(nullptr)}};
  out["files"] = Json::array();
  std::size_t drifted = 0;
  for (const auto& f : files) {
    Json file = {{"file", f.file},
                 {"drift", f.drift},
                 {"missing", f.missing},
                 {"undecided", f.undecided},
                 {"parameters", Json::object()}};
    for (const auto& c : f.parameters) {
      file["parameters"][c.name] = {{"base", c.base},       {"base_std", c.base_std},
                                    {"value", c.value},     {"std", c.value_std},
                                    {"relative_change", Number(c.relative_change)},
                                    {"z", Number(c.z)},     {"drift", c.drift}};
    }
    out["files"].push_back(file);
    drifted += f.drift ? 1 : 0;
  }
  out["drifted"] = drifted;
  return out;
}

std::vector<PlotPanel> ComparisonPanels(const std::vector<FileComparison>& files, const DriftGate& gate) {
  std::vector<PlotPanel> panels;
  if (files.empty()) return panels;
  for (const auto& first : files.front().parameters) {
    PlotPanel panel;
    panel.title = first.name;
    panel.y_label = "change from base [%]";
    PlotLine change{"relative change", {}, {}}, upper{"+2 std", {}, {}}, lower{"-2 std", {}, {}};
    change.dots = true;
    for (std::size_t i = 0; i < files.size(); ++i) {
      for (const auto& c : files[i].parameters) {
        if (c.name != first.name || !std::isfinite(c.relative_change)) continue;
        const double x = static_cast<double>(i + 1);
        const double band = c.base != 0.0 ? 200.0 * std::hypot(c.base_std, c.value_std) / std::abs(c.base) : 0.0;
        change.x.push_back(x);
        change.y.push_back(100.0 * c.relative_change);
        upper.x.push_back(x);
        upper.y.push_back(band);
        lower.x.push_back(x);
        lower.y.push_back(-band);
      }
    }
    panel.lines = {change, upper, lower};
    if (gate.max_percent) {
      const double n = static_cast<double>(files.size());
      panel.lines.push_back({fmt::format("+{:g} %", *gate.max_percent), {1.0, n}, {*gate.max_percent, *gate.max_percent}});
      panel.lines.push_back({fmt::format("-{:g} %", *gate.max_percent), {1.0, n}, {-*gate.max_percent, -*gate.max_percent}});
    }
    panels.push_back(std::move(panel));
  }
  return panels;
}

}  // namespace driveid
