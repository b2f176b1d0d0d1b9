#include "logs/formats/wpilog_routines.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/order_statistics.h"

namespace driveid {
namespace {

constexpr std::string_view kStatePrefix = "sysid-test-state-";

bool StartsWith(const std::string& text, std::string_view prefix) { return text.compare(0, prefix.size(), prefix) == 0; }
bool EndsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string Lower(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

bool IsNumeric(const std::string& type) {
  return type == "double" || type == "float" || type == "int64" || type == "boolean";
}

const WpilogEntry* FindEntry(const WpilogIndex& index, const std::string& name) {
  for (const auto& e : index.entries) {
    if (e.name == name) return &e;
  }
  return nullptr;
}

// The last path component of an entry name ("/Drive/Module0/DriveAppliedVolts"
// -> its offset of "DriveAppliedVolts").
std::size_t ComponentStart(const std::string& name) {
  const auto slash = name.find_last_of('/');
  return slash == std::string::npos ? 0 : slash + 1;
}

// SysIdRoutine's own names.
std::vector<WpilogRoutine> SysIdRoutines(const WpilogIndex& index) {
  std::vector<WpilogRoutine> out;
  std::set<std::string> seen;
  for (const auto& e : index.entries) {
    if (!StartsWith(e.name, kStatePrefix) || e.type != "string") continue;
    const std::string mechanism = e.name.substr(kStatePrefix.size());
    if (!seen.insert(mechanism).second) continue;
    WpilogRoutine routine{mechanism, e.name, {}, fmt::format("SysIdRoutine '{}'", mechanism)};
    std::set<std::string> motors;
    const std::string suffix = "-" + mechanism;
    for (const auto& v : index.entries) {
      if (!StartsWith(v.name, "voltage-") || !EndsWith(v.name, suffix) || v.name.size() <= 8 + suffix.size()) continue;
      const std::string motor = v.name.substr(8, v.name.size() - 8 - suffix.size());
      const WpilogMotor m{motor, v.name, "position-" + motor + suffix, "velocity-" + motor + suffix};
      if (FindEntry(index, m.position) != nullptr && FindEntry(index, m.velocity) != nullptr &&
          motors.insert(motor).second) {
        routine.motors.push_back(m);
      }
    }
    out.push_back(std::move(routine));
  }
  return out;
}

// The entries the user named.
WpilogRoutine GivenRoutine(const std::string& path, const WpilogIndex& index, const WpilogEntries& given) {
  const std::pair<const char*, const std::string*> numeric[] = {
      {"voltage", &given.voltage}, {"position", &given.position}, {"velocity", &given.velocity}};
  std::vector<std::string> names;
  for (const auto& e : index.entries) names.push_back(e.name);
  const auto listing = [&] {
    return names.size() <= 40 ? fmt::format("{}", fmt::join(names, ", "))
                              : fmt::format("{}, ... ({} in all; inspect lists them)",
                                            fmt::join(names.begin(), names.begin() + 40, ", "), names.size());
  };
  for (const auto& [role, name] : numeric) {
    if (name->empty()) {
      throw OptionError(fmt::format("‹entry›: {} needs the {} entry too (‹entry› {}=NAME; the log's entries: {})", path,
                                    role, role, listing()));
    }
    const WpilogEntry* e = FindEntry(index, *name);
    if (e == nullptr) {
      throw InputError(fmt::format("{}: no entry '{}' (‹entry› {}); the log's entries: {}", path, *name, role, listing()));
    }
    if (!IsNumeric(e->type)) {
      throw InputError(fmt::format("{}: entry '{}' (‹entry› {}) is of type {}, not a number (double, float, int64, "
                                   "boolean)",
                                   path, *name, role, e->type));
    }
  }
  if (!given.state.empty()) {
    const WpilogEntry* e = FindEntry(index, given.state);
    if (e == nullptr) {
      throw InputError(fmt::format("{}: no entry '{}' (‹entry› state); the log's entries: {}", path, given.state,
                                   listing()));
    }
    if (e->type != "string") {
      throw InputError(fmt::format("{}: entry '{}' (‹entry› state) is of type {}, not a string of SysId's state "
                                   "names",
                                   path, given.state, e->type));
    }
  }
  return {"", given.state, {{given.voltage, given.voltage, given.position, given.velocity}}, "the entries given (‹entry›)"};
}

// Where a role word starts in an entry's last component (lower case), or npos.
std::size_t RoleAt(const std::string& name, const char* role) {
  const std::size_t begin = ComponentStart(name);
  const std::string component = Lower(std::string_view(name).substr(begin));
  if (std::string_view(role) == "voltage") {
    for (const char* word : {"appliedvolt", "volt"}) {
      const auto at = component.find(word);
      if (at != std::string::npos) return begin + at;
    }
    return std::string::npos;
  }
  const auto at = component.find(role);
  return at == std::string::npos ? std::string::npos : begin + at;
}

// AdvantageKit's naming: one state entry ...SysIdState and the motors whose
// three numeric entries share their name up to the role word.
std::vector<WpilogRoutine> AdvantageKitRoutines(const WpilogIndex& index) {
  std::vector<const WpilogEntry*> states;
  for (const auto& e : index.entries) {
    if (e.type == "string" && Lower(e.name).find("sysidstate") != std::string::npos) states.push_back(&e);
  }
  if (states.size() != 1) return {};
  std::map<std::string, WpilogMotor> by_key;
  std::set<std::string> ambiguous;  // two entries for one role of a motor
  for (const auto& e : index.entries) {
    if (!IsNumeric(e.type)) continue;
    for (const char* role : {"voltage", "position", "velocity"}) {
      const std::size_t at = RoleAt(e.name, role);
      if (at == std::string::npos) continue;
      const std::string key = e.name.substr(0, at);
      WpilogMotor& m = by_key[key];
      const std::string_view r(role);
      std::string& slot = r == "voltage" ? m.voltage : r == "position" ? m.position : m.velocity;
      if (!slot.empty()) ambiguous.insert(key);
      slot = e.name;
      break;
    }
  }
  WpilogRoutine routine{states.front()->name, states.front()->name, {},
                        fmt::format("AdvantageKit's naming (state entry '{}')", states.front()->name)};
  for (auto& [key, m] : by_key) {
    if (m.voltage.empty() || m.position.empty() || m.velocity.empty() || ambiguous.count(key) > 0) continue;
    m.name = key;
    routine.motors.push_back(m);
  }
  if (routine.motors.empty()) return {};
  return {routine};
}

}  // namespace

std::vector<WpilogRoutine> FindWpilogRoutines(const std::string& path, const WpilogIndex& index,
                                              const WpilogSelection& selection) {
  if (selection.entries.Any()) return {GivenRoutine(path, index, selection.entries)};
  std::vector<WpilogRoutine> routines = SysIdRoutines(index);
  if (routines.empty()) routines = AdvantageKitRoutines(index);
  return routines;
}

std::string CanonicalSysIdState(std::string_view value) {
  std::string word;
  for (char c : value) {
    if (std::isalnum(static_cast<unsigned char>(c))) word += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  // "State.kQuasistaticForward", "kQuasistaticForward", "quasistatic-forward".
  if (StartsWith(word, "state")) word = word.substr(5);
  if (StartsWith(word, "sysidroutinelogstate")) word = word.substr(20);
  if (!word.empty() && word[0] == 'k') word = word.substr(1);
  static const std::map<std::string, std::string> kStates = {{"quasistaticforward", "quasistatic-forward"},
                                                             {"quasistaticreverse", "quasistatic-reverse"},
                                                             {"dynamicforward", "dynamic-forward"},
                                                             {"dynamicreverse", "dynamic-reverse"},
                                                             {"none", "none"}};
  const auto found = kStates.find(word);
  return found == kStates.end() ? std::string() : found->second;
}

std::vector<std::pair<std::int64_t, std::string>> StatesFromVoltage(const std::vector<double>& t_us,
                                                                   const std::vector<double>& volts,
                                                                   std::vector<std::string>& notes) {
  std::vector<std::pair<std::int64_t, std::string>> states;
  const std::size_t n = std::min(t_us.size(), volts.size());
  double largest = 0.0;
  for (std::size_t k = 0; k < n; ++k) largest = std::max(largest, std::abs(volts[k]));
  if (n < 2 || !(largest > 0.0)) return states;
  std::vector<double> steps;
  for (std::size_t k = 1; k < n; ++k) steps.push_back(t_us[k] - t_us[k - 1]);
  // A pause in the records (the routine logs only while a test runs), or the
  // voltage at rest (within 2 % of its largest) or changing sign, ends a test.
  const double gap = std::max(10.0 * Median(steps), 0.1e6);
  const double rest = 0.02 * largest;
  std::vector<std::string> found;
  std::size_t k = 0;
  while (k < n) {
    if (!(std::abs(volts[k]) > rest)) {
      ++k;
      continue;
    }
    std::size_t end = k + 1;
    while (end < n && std::abs(volts[end]) > rest && (volts[end] > 0) == (volts[k] > 0) &&
           t_us[end] - t_us[end - 1] <= gap) {
      ++end;
    }
    const std::size_t count = end - k;
    if (count >= 5) {
      // A ramp from rest rises: its last tenth lies well above its first;
      // a step holds its level from its first records on.
      const std::size_t tenth = std::max<std::size_t>(1, count / 10);
      std::vector<double> first, last, middle;
      for (std::size_t j = k; j < k + tenth; ++j) first.push_back(std::abs(volts[j]));
      for (std::size_t j = end - tenth; j < end; ++j) last.push_back(std::abs(volts[j]));
      for (std::size_t j = k + tenth; j < end - tenth; ++j) middle.push_back(std::abs(volts[j]));
      const double a = Median(first), b = Median(last);
      const std::string direction = volts[k] > 0 ? "forward" : "reverse";
      std::string test;
      if (b > 1.5 * a) {
        test = "quasistatic-" + direction;
      } else if (!middle.empty()) {
        const auto [lo, hi] = std::minmax_element(middle.begin(), middle.end());
        if (*hi - *lo <= 0.2 * Median(middle)) test = "dynamic-" + direction;
      }
      if (!test.empty()) {
        const auto begin = static_cast<std::int64_t>(t_us[k]);
        const auto stop = end < n ? static_cast<std::int64_t>(t_us[end]) : static_cast<std::int64_t>(t_us[end - 1]) + 1;
        states.emplace_back(begin, test);
        states.emplace_back(stop, "none");
        found.push_back(fmt::format("{} {:.3f} .. {:.3f} s", test, t_us[k] * 1e-6, t_us[end - 1] * 1e-6));
      }
    }
    k = end;
  }
  notes.push_back(found.empty()
                      ? std::string("tests from the voltage pattern (no state entry): none found (a ramp from rest is "
                                    "quasistatic, a held step dynamic; name the state entry with ‹entry› state=NAME)")
                      : fmt::format("tests found from the voltage pattern (no state entry; a ramp from rest is "
                                    "quasistatic, a held step dynamic, the sign the direction): {}",
                                    fmt::join(found, ", ")));
  return states;
}

std::string WpilogPositionUnit(const std::string& metadata, const std::string& entry_name) {
  static const std::map<std::string, std::string> kNames = {
      {"Meter", "Meters"},   {"Meters", "Meters"},     {"Rotation", "Rotations"}, {"Rotations", "Rotations"},
      {"Radian", "Radians"}, {"Radians", "Radians"},   {"Degree", "Degrees"},     {"Degrees", "Degrees"},
      {"Foot", "Feet"},      {"Feet", "Feet"},         {"Inch", "Inches"},        {"Inches", "Inches"},
      {"Millimeter", "mm"},  {"Millimeters", "mm"}};
  const auto found = kNames.find(metadata);
  if (found != kNames.end()) return found->second;
  if (!metadata.empty() && metadata.find('{') == std::string::npos) return metadata;
  // AdvantageKit's suffixes after the role word.
  const std::size_t at = RoleAt(entry_name, "position");
  if (at == std::string::npos) return "";
  const std::string suffix = Lower(std::string_view(entry_name).substr(at + 8));
  static const std::map<std::string, std::string> kSuffixes = {
      {"rad", "Radians"},     {"radians", "Radians"}, {"rot", "Rotations"}, {"rots", "Rotations"},
      {"rotations", "Rotations"}, {"meters", "Meters"}, {"m", "Meters"},    {"deg", "Degrees"},
      {"degrees", "Degrees"}, {"inches", "Inches"},   {"feet", "Feet"}};
  const auto unit = kSuffixes.find(suffix);
  return unit == kSuffixes.end() ? std::string() : unit->second;
}

}  // namespace driveid
