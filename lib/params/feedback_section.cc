#include "params/feedback_section.h"

#include <algorithm>
#include <tuple>

#include <fmt/format.h>

#include "core/errors.h"
#include "params/parameter_sections.h"
#include "models/feedforward.h"

namespace driveid {
namespace {

using namespace section_io;

constexpr std::size_t kMaxCoefficients = 16;

std::string KnownKeys() {
  std::string known = "loop, preset, effort_unit, position_unit, numerator, denominator, numerator_z, denominator_z";
  for (const auto& k : kFeedbackKeys) known += std::string(", ") + k.key;
  return known;
}

std::string ParseName(const std::string& path, const std::string& key, const YAML::Node& node) {
  const std::string name = "feedback." + key;
  if (!node.IsScalar()) throw InputError(fmt::format("{}: {}: expected a name", Where(path, node), name));
  const std::string value = node.Scalar();
  if (key == "loop" && std::find_if(kFeedbackLoops.begin(), kFeedbackLoops.end(),
                                    [&](const char* loop) { return value == loop; }) == kFeedbackLoops.end()) {
    throw InputError(fmt::format("{}: {}: \"{}\": expected velocity, position or speed", Where(path, node), name,
                                 UnitTextProblem(value).empty() ? value : "?"));
  }
  if (!value.empty() && !UnitTextProblem(value).empty()) {
    throw InputError(fmt::format("{}: {}: not a name: {} (letters, digits, blanks and / ^ * . _ ( ) % + -)",
                                 Where(path, node), name, UnitTextProblem(value)));
  }
  return value;
}

std::vector<double> ParseCoefficients(const std::string& path, const std::string& key, const YAML::Node& node) {
  const std::string name = "feedback." + key;
  if (!node.IsSequence() || node.size() == 0 || node.size() > kMaxCoefficients) {
    throw InputError(fmt::format("{}: {}: expected a list of 1 to {} numbers", Where(path, node), name, kMaxCoefficients));
  }
  std::vector<double> out;
  for (const auto& c : node) out.push_back(ParseNumber(path, name, c));
  return out;
}

FeedbackValue ParseValue(const std::string& path, const std::string& key, const YAML::Node& node) {
  const std::string name = "feedback." + key;
  FeedbackValue value;
  value.key = key;
  if (node.IsMap()) {
    for (const auto& entry : node) {
      const std::string sub = entry.first.Scalar();
      if (sub != "value" && sub != "std" && sub != "ci95") {
        throw InputError(fmt::format("{}: {}.{}: unknown key (known: value, std, ci95)", Where(path, entry.first), name, sub));
      }
    }
    if (!node["value"]) throw InputError(fmt::format("{}: {}: needs a value", Where(path, node), name));
    value.value = ParseNumber(path, name + ".value", node["value"]);
    if (node["std"]) value.standard_error = ParseStandardError(path, name + ".std", node["std"]);
    if (const YAML::Node ci = node["ci95"]) {
      if (!ci.IsSequence() || ci.size() != 2) {
        throw InputError(fmt::format("{}: {}.ci95: expected [low, high]", Where(path, ci), name));
      }
      value.ci95_low = ParseNumber(path, name + ".ci95", ci[0]);
      value.ci95_high = ParseNumber(path, name + ".ci95", ci[1]);
      if (!(value.ci95_low <= value.value && value.value <= value.ci95_high)) {
        throw InputError(fmt::format("{}: {}.ci95: [{}, {}] does not hold the value {}", Where(path, ci), name,
                                     value.ci95_low, value.ci95_high, value.value));
      }
    }
  } else {
    value.value = ParseNumber(path, name, node);
  }
  return value;
}


}  // namespace

FeedbackController ParseFeedbackSection(const std::string& path, const YAML::Node& node) {
  CheckMapping(path, "feedback", node);
  FeedbackController out;
  for (const auto& item : node) {
    const std::string key = item.first.Scalar();
    if (key == "loop" || key == "preset" || key == "effort_unit" || key == "position_unit") {
      const std::string value = ParseName(path, key, item.second);
      (key == "loop" ? out.loop : key == "preset" ? out.preset : key == "effort_unit" ? out.effort_unit
                                                                                      : out.position_unit) = value;
    } else if (key == "numerator" || key == "denominator" || key == "numerator_z" || key == "denominator_z") {
      (key == "numerator" ? out.numerator : key == "denominator" ? out.denominator
                                          : key == "numerator_z" ? out.numerator_z : out.denominator_z) =
          ParseCoefficients(path, key, item.second);
    } else if (FindFeedbackKey(key)) {
      out.values.push_back(ParseValue(path, key, item.second));
      if (key == "period" && !(out.values.back().value > 0.0)) {
        throw InputError(fmt::format("{}: feedback.period = {}: a controller period is > 0 s", Where(path, item.second),
                                     out.values.back().value));
      }
    } else {
      throw InputError(fmt::format("{}: feedback.{}: unknown key (known: {})", Where(path, item.first), key, KnownKeys()));
    }
  }
  if (out.loop.empty()) throw InputError(fmt::format("{}: feedback.loop: missing (velocity, position or speed)", Where(path, node)));
  // Written in the order of kFeedbackKeys whatever order was read.
  std::stable_sort(out.values.begin(), out.values.end(), [](const FeedbackValue& a, const FeedbackValue& b) {
    return FindFeedbackKey(a.key) < FindFeedbackKey(b.key);
  });
  return out;
}

std::string FormatFeedbackSection(const FeedbackController& f) {
  for (const auto& [field, name] : {std::pair{"loop", &f.loop}, std::pair{"preset", &f.preset},
                                     std::pair{"effort_unit", &f.effort_unit},
                                     std::pair{"position_unit", &f.position_unit}}) {
    if (!UnitTextProblem(*name).empty()) {
      throw OutputError(fmt::format("feedback.{}: not a name: {}; nothing written", field, UnitTextProblem(*name)));
    }
  }
  // What the reader refuses is not written (ParseFeedbackSection).
  if (std::find_if(kFeedbackLoops.begin(), kFeedbackLoops.end(), [&](const char* loop) { return f.loop == loop; }) ==
      kFeedbackLoops.end()) {
    throw OutputError(fmt::format("feedback.loop: {}: not one of {}; nothing written", f.loop,
                                  fmt::join(kFeedbackLoops, ", ")));
  }
  std::string out = "feedback:  # the controller `gains` designed: docs/models.md#feedback-gains\n";
  out += fmt::format("  loop: {}\n", f.loop);
  if (!f.preset.empty()) out += fmt::format("  preset: {}\n", f.preset);
  out += fmt::format("  effort_unit: \"{}\"\n  position_unit: \"{}\"\n", f.effort_unit, f.position_unit);
  for (const auto& v : f.values) {
    const FeedbackKey* key = FindFeedbackKey(v.key);
    if (!key) throw OutputError(fmt::format("feedback.{}: unknown key; nothing written", v.key));
    const std::string name = "feedback." + v.key;
    const std::string unit = FeedbackKeyUnit(*key, f);
    const std::string comment = unit.empty() ? key->description : fmt::format("{} [{}]", key->description, unit);
    if (key->gain) {
      const std::string interval =
          v.HasInterval() ? fmt::format(", ci95: [{}, {}]", Number(Writable(name + ".ci95", v.ci95_low)),
                                        Number(Writable(name + ".ci95", v.ci95_high)))
                          : "";
      out += fmt::format("  {}: {{value: {}, std: {}{}}}  # {}\n", v.key, Number(Writable(name, v.value)),
                         fmt::format("{:.6g}", Writable(name + ".std", v.standard_error)), interval, comment);
    } else {
      out += fmt::format("  {}: {}  # {}\n", v.key, Number(Writable(name, v.value)), comment);
    }
  }
  for (const auto& [key, coefficients, comment] :
       {std::tuple{"numerator", &f.numerator, "C(s), highest power of s first"},
        std::tuple{"denominator", &f.denominator, "C(s), highest power of s first"},
        std::tuple{"numerator_z", &f.numerator_z, "C(z) at the period, powers z^0, z^-1, ...: u[k] = sum b_i e[k-i]"},
        std::tuple{"denominator_z", &f.denominator_z, "C(z): - sum_(i>0) a_i u[k-i]; a_0 = 1"}}) {
    if (coefficients->empty()) continue;
    std::string list;
    for (double c : *coefficients) list += (list.empty() ? "" : ", ") + Number(Writable(std::string("feedback.") + key, c));
    out += fmt::format("  {}: [{}]  # {}\n", key, list, comment);
  }
  return out;
}

}  // namespace driveid
