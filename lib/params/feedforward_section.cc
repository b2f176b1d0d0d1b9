// The feed-forward section: units as strings, each gain {value, std}.
#include "params/feedforward_section.h"

#include <cstddef>

#include <fmt/format.h>

#include "core/errors.h"
#include "params/parameter_sections.h"

namespace driveid {
namespace {

constexpr std::size_t kMaxUnitBytes = 64;  // feedforward.effort_unit, position_unit

}  // namespace

using namespace section_io;

Feedforward ParseFeedforward(const std::string& path, const YAML::Node& node) {
  CheckMapping(path, "feedforward", node);
  Feedforward out;
  for (const auto& item : node) {
    const std::string key = item.first.Scalar();
    const std::string name = "feedforward." + key;
    if (key == "mechanism") {
      const std::string value = item.second.IsScalar() ? item.second.Scalar() : std::string();
      if (value != "simple" && value != "elevator" && value != "arm") {
        throw InputError(fmt::format("{}: {}: expected simple, elevator or arm (SysId's analysis type)",
                                     Where(path, item.second), name));
      }
      out.mechanism = value;
      continue;
    }
    if (key == "effort_unit" || key == "position_unit" || key == "law") {
      if (!item.second.IsScalar()) throw InputError(fmt::format("{}: {}: expected a name", Where(path, item.second), name));
      const std::string value = item.second.Scalar();
      if (value.size() > kMaxUnitBytes) {
        throw InputError(fmt::format("{}: {}: {} bytes: at most {}", Where(path, item.second), name, value.size(),
                                     kMaxUnitBytes));
      }
      if (key != "law" && !value.empty() && !UnitTextProblem(value).empty()) {
        throw InputError(fmt::format("{}: {}: not a unit name: {} (units hold letters, digits, blanks and "
                                     "/ ^ * . _ ( ) % + -)",
                                     Where(path, item.second), name, UnitTextProblem(value)));
      }
      if (key == "law" && value != kAxisFeedforwardLaw && value != kCDriveCompensationLaw) {
        throw InputError(fmt::format("{}: {}: \"{}\": expected {} or {}", Where(path, item.second), name, value,
                                     kAxisFeedforwardLaw, kCDriveCompensationLaw));
      }
      (key == "effort_unit" ? out.effort_unit : key == "law" ? out.law : out.position_unit) = value;
      continue;
    }
    if (std::find(kFeedforwardKeys.begin(), kFeedforwardKeys.end(), key) == kFeedforwardKeys.end()) {
      throw InputError(fmt::format("{}: {}: unknown key (known: law, effort_unit, position_unit, mechanism, {})",
                                   Where(path, item.first), name, fmt::join(kFeedforwardKeys, ", ")));
    }
    CheckKeys(path, name, item.second, {"value", "std"});
    if (!item.second["value"]) throw InputError(fmt::format("{}: {}: needs a value", Where(path, item.second), name));
    FeedforwardGain gain;
    gain.key = key;
    gain.value = ParseNumber(path, name + ".value", item.second["value"]);
    if (item.second["std"]) gain.standard_error = ParseStandardError(path, name + ".std", item.second["std"]);
    out.gains.push_back(gain);
  }
  for (auto& gain : out.gains) gain.unit = FeedforwardUnit(gain.key, out.effort_unit, out.position_unit);
  return out;
}

std::string FormatFeedforward(const Feedforward& f) {
  for (const auto& [name, unit] : {std::pair{"effort_unit", &f.effort_unit}, std::pair{"position_unit", &f.position_unit}}) {
    if (unit->size() > kMaxUnitBytes) {
      throw OutputError(fmt::format("feedforward.{}: {} bytes, a parameter file holds at most {}; nothing written", name,
                                    unit->size(), kMaxUnitBytes));
    }
    if (!unit->empty() && !UnitTextProblem(*unit).empty()) {
      throw OutputError(fmt::format("feedforward.{}: not a unit name: {}; nothing written", name, UnitTextProblem(*unit)));
    }
  }
  std::string out =
      f.law == kCDriveCompensationLaw
          ? "feedforward:  # eq. (31): tau_I = beta w_I + delta RL{sgn DZ(w_I)} + gamma_half (w_I - w_J) + eta "
            "RL{sgn DZ(w_I - w_J)}, docs/models.md#c-drive\n"
          : "feedforward:  # u = Ks sgn(v) + Kv v + Ka a + Kg cos(q - Kg_angle) + offset, "
            "docs/models.md#feed-forward\n";
  out += fmt::format("  law: {}\n  effort_unit: {}\n  position_unit: {}\n", f.law, Quoted(f.effort_unit),
                     Quoted(f.position_unit));
  if (!f.mechanism.empty()) out += fmt::format("  mechanism: {}  # SysId's analysis type of the logs\n", f.mechanism);
  for (const auto& g : f.gains) {
    const std::string name = "feedforward." + g.key;
    out += fmt::format("  {}: {{value: {}, std: {}}}  # {}\n", g.key, Number(Writable(name, g.value)),
                       Short(Writable(name + ".std", g.standard_error)),
                       Comment(FeedforwardUnit(g.key, f.effort_unit, f.position_unit)));
  }
  return out;
}

}  // namespace driveid
