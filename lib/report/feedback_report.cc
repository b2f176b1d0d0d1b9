#include "report/feedback_report.h"

#include <fmt/format.h>

#include "control/feedback_gains.h"

namespace driveid {

std::string FormatFeedbackReport(const FeedbackController& f) {
  std::string out = fmt::format("feedback ({} loop, preset {}; docs/models.md#feedback-gains):\n", f.loop, f.preset);
  for (const auto& v : f.values) {
    const FeedbackKey* key = FindFeedbackKey(v.key);
    if (key && key->gain) {
      const std::string interval = v.HasInterval() ? fmt::format("  95 % [{:.6g}, {:.6g}]", v.ci95_low, v.ci95_high) : "";
      out += fmt::format("  {:<24} {:>12.6g} +- {:<10.3g} {}{}\n", v.key, v.value, v.standard_error,
                         FeedbackGainUnit(f, v.key), interval);
    } else {
      out += fmt::format("  {:<24} {:>12.6g}    {:<10} {}\n", v.key, v.value, key ? FeedbackKeyUnit(*key, f) : "",
                         key ? key->description : "");
    }
  }
  if (!f.numerator.empty()) {
    out += fmt::format("  C(s) numerator   [{:.6g}]\n  C(s) denominator [{:.6g}]\n", fmt::join(f.numerator, ", "),
                       fmt::join(f.denominator, ", "));
  }
  if (!f.numerator_z.empty()) {
    out += fmt::format("  C(z) numerator   [{:.10g}]  (z^0, z^-1, ...)\n  C(z) denominator [{:.10g}]\n",
                       fmt::join(f.numerator_z, ", "), fmt::join(f.denominator_z, ", "));
  }
  return out;
}

Json FeedbackReportJson(const FeedbackController& f) {
  Json out = Json::object();
  out["loop"] = f.loop;
  out["preset"] = f.preset;
  out["effort_unit"] = f.effort_unit;
  out["position_unit"] = f.position_unit;
  Json gains = Json::object(), settings = Json::object(), controller = Json::object();
  if (!f.numerator.empty()) controller = {{"numerator", f.numerator}, {"denominator", f.denominator}};
  if (!f.numerator_z.empty()) {
    controller["numerator_z"] = f.numerator_z;
    controller["denominator_z"] = f.denominator_z;
  }
  for (const auto& v : f.values) {
    const FeedbackKey* key = FindFeedbackKey(v.key);
    const bool gain = key && key->gain;
    // The speed loop's notch and margins describe its controller C(s).
    const bool design = v.key.rfind("notch", 0) == 0 || v.key == "crossover_hz" ||
                        v.key.find("margin") != std::string::npos;
    if (gain) {
      gains[v.key] = {{"value", v.value}, {"std", v.standard_error}, {"unit", FeedbackGainUnit(f, v.key)}};
      if (v.HasInterval()) gains[v.key]["ci95"] = {v.ci95_low, v.ci95_high};
    }
    else if (design) controller[v.key] = v.value;
    else settings[v.key] = v.value;
  }
  out["feedback"] = gains;
  out["settings"] = settings;
  if (!controller.empty()) out["controller"] = controller;
  return out;
}

}  // namespace driveid
