#include "io/serial_robot_section.h"
#include "io/robot_coupling_section.h"
#include "io/parameter_file.h"

#include <algorithm>
#include <cctype>
#include <array>
#include <charconv>
#include <functional>
#include <cmath>
#include <limits>
#include <set>
#include <string_view>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "core/errors.h"
#include "core/estimate_record.h"
#include "core/fit_section.h"
#include "io/csv_log.h"
#include "io/feedback_section.h"
#include "io/parameter_sections.h"

namespace driveid {

namespace section_io {

std::string Where(const std::string& path, const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  if (mark.is_null()) return path;
  return fmt::format("{}:{}:{}", path, mark.line + 1, mark.column + 1);
}

double ParseNumber(const std::string& path, const std::string& name, const YAML::Node& node) {
  if (!node.IsScalar()) throw InputError(fmt::format("{}: {}: expected a number", Where(path, node), name));
  const std::string& text = node.Scalar();
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  if (begin != end && *begin == '+') ++begin;
  double value = 0.0;
  const auto result = std::from_chars(begin, end, value);
  if (result.ec != std::errc() || result.ptr != end || !std::isfinite(value)) {
    throw InputError(fmt::format("{}: {}: not a finite number: \"{}\"", Where(path, node), name,
                                 text.substr(0, 40)));
  }
  // Products and quotients of a few parameters (k_eq, omega_n, ...) must stay
  // finite: values are 0 or within 1e-100 <= |v| <= 1e100 (docs/formats.md).
  if (value != 0.0 && !(std::abs(value) >= kSmallestParameterMagnitude && std::abs(value) <= kLargestParameterMagnitude)) {
    throw InputError(fmt::format("{}: {} = {}: outside the range of parameter values (0 or 1e-100 <= |value| <= 1e100)",
                                 Where(path, node), name, text.substr(0, 40)));
  }
  return value;
}

double ParseStandardError(const std::string& path, const std::string& name, const YAML::Node& node) {
  const double value = ParseNumber(path, name, node);
  if (value < 0.0) throw InputError(fmt::format("{}: {} = {}: a standard error is >= 0", Where(path, node), name, value));
  return value;
}

// Refuses non-mappings, duplicate and non-scalar keys.
void CheckMapping(const std::string& path, const std::string& name, const YAML::Node& node) {
  if (!node.IsMap()) throw InputError(fmt::format("{}: {}: expected a mapping of keys", Where(path, node), name));
  std::set<std::string> seen;
  for (const auto& item : node) {
    if (!item.first.IsScalar()) throw InputError(fmt::format("{}: {}: keys must be names", Where(path, item.first), name));
    if (!seen.insert(item.first.Scalar()).second) {
      throw InputError(fmt::format("{}: {}.{}: key appears twice", Where(path, item.first), name, item.first.Scalar()));
    }
  }
}

std::string Number(double value) { return fmt::format("{}", value); }

std::string YamlName(const std::string& name) {
  bool plain = !name.empty();
  for (char c : name) plain = plain && (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.');
  if (plain) return name;
  std::string quoted = "\"";
  for (char c : name) {
    if (c == '"' || c == '\\') quoted += '\\';
    quoted += c;
  }
  return quoted + "\"";
}

std::string ParseText(const std::string& path, const std::string& name, const YAML::Node& node) {
  if (!node.IsScalar()) throw InputError(fmt::format("{}: {}: expected text", Where(path, node), name));
  return node.Scalar();
}

// A value as the reader will accept it (ParseNumber): finite, 0 or within
// 1e-100 <= |v| <= 1e100; else nothing is written.
double Writable(const std::string& name, double value) {
  if (!std::isfinite(value) ||
      (value != 0.0 && !(std::abs(value) >= kSmallestParameterMagnitude && std::abs(value) <= kLargestParameterMagnitude))) {
    throw OutputError(fmt::format("{} = {}: outside what a parameter file holds (finite, 0 or 1e-100 <= |value| <= "
                                  "1e100); nothing written (rescale the data)",
                                  name, value));
  }
  return value;
}

}  // namespace section_io

namespace {
using namespace section_io;



// CheckMapping, and every key one of `known`.
void CheckKeys(const std::string& path, const std::string& name, const YAML::Node& node,
               const std::vector<std::string>& known) {
  CheckMapping(path, name, node);
  for (const auto& item : node) {
    if (std::find(known.begin(), known.end(), item.first.Scalar()) == known.end()) {
      throw InputError(fmt::format("{}: {}.{}: unknown key (known: {})", Where(path, item.first), name,
                                   item.first.Scalar().substr(0, 64), fmt::join(known, ", ")));
    }
  }
}



CDriveControlSection ParseControl(const std::string& path, const YAML::Node& node) {
  CDriveControlSection control;
  const auto others = ParseSection(path, "cdrive.control", node, CDriveControlParameterTable(), {"law"}, control);
  for (const auto& [key, value] : others) {
    const std::string law = value.IsScalar() ? value.Scalar() : "";
    if (law == "PI") control.law = ControlLaw::kPI;
    else if (law == "PD") control.law = ControlLaw::kPD;
    else if (law == "PID") control.law = ControlLaw::kPID;
    else throw InputError(fmt::format("{}: cdrive.control.law: must be PI, PD or PID", Where(path, value)));
  }
  return control;
}

// Length of the valid UTF-8 sequence starting at text[i], or 0.
std::size_t Utf8Length(const std::string& text, std::size_t i) {
  const unsigned char lead = static_cast<unsigned char>(text[i]);
  std::size_t length = 0;
  if (lead >= 0xC2 && lead <= 0xDF) length = 2;
  else if (lead >= 0xE0 && lead <= 0xEF) length = 3;
  else if (lead >= 0xF0 && lead <= 0xF4) length = 4;
  else return 0;
  if (i + length > text.size()) return 0;
  for (std::size_t k = 1; k < length; ++k) {
    if ((static_cast<unsigned char>(text[i + k]) & 0xC0) != 0x80) return 0;
  }
  return length;
}

// A YAML double-quoted string: control characters and bytes that are not
// UTF-8 (a file name may hold any bytes) are escaped as \xNN.
std::string Quoted(const std::string& text) {
  std::string out = "\"";
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    const unsigned char u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (u < 0x20 || u == 0x7F) {
      out += fmt::format("\\x{:02x}", u);
    } else if (u >= 0x80) {
      const std::size_t length = Utf8Length(text, i);
      if (length == 0) {
        out += fmt::format("\\x{:02x}", u);
      } else {
        out.append(text, i, length);
        i += length - 1;
      }
    } else {
      out += c;
    }
  }
  return out + "\"";
}

constexpr std::size_t kMaxUnitBytes = 64;  // feedforward.effort_unit, position_unit
constexpr std::size_t kMaxParameterFileBytes = 1 << 20, kMaxParameterLineBytes = 1 << 16;  // what the reader accepts

// Provenance text (the command line, notes) is information, not data: cut
// beyond `limit` bytes, saying so, so that a line stays within what the
// reader accepts (64 KiB).
constexpr std::size_t kMaxProvenanceText = 4096;
std::string Abbreviated(const std::string& text, std::size_t limit) {
  if (text.size() <= limit) return text;
  std::size_t cut = limit;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;  // not inside a UTF-8 character
  return fmt::format("{} ... ({} bytes in all)", text.substr(0, cut), text.size());
}

// Text for a comment: as is when it is printable ASCII, else quoted and
// escaped — a unit read from a log must not end the comment and start a key.
std::string Comment(const std::string& text) {
  const bool plain = std::all_of(text.begin(), text.end(), [](char c) { return c >= 0x20 && c < 0x7F; });
  return plain ? text : Quoted(text);
}


std::string Short(double value) { return fmt::format("{:.6g}", value); }

// An estimate record (core/estimate_record.h) as a YAML flow map,
// "{value: V, std: S, ci95: [L, H]}": the value to the last bit, the rest
// to six digits; `path` names it in messages (fit.estimates.NAME).
struct YamlRecordWriter {
  std::string path, out;
  void Next() { out += out.empty() ? "{" : ", "; }
  void Scalar(const char* key, EstimateField field, const double& v) {
    Next();
    out += field == EstimateField::kValue ? fmt::format("{}: {}", key, Number(Writable(path, v)))
                                          : fmt::format("{}: {}", key, Short(Writable(path + "." + key, v)));
  }
  void Interval(const char* key, const double& low, const double& high) {
    Next();
    const std::string name = path + "." + key;
    out += fmt::format("{}: [{}, {}]", key, Short(Writable(name, low)), Short(Writable(name, high)));
  }
  std::string Close() const { return out + "}"; }
};

// An estimate record read back from its YAML node `node` (`name`:
// fit.estimates.NAME): the scalars required, a standard error >= 0, the
// interval optional and ordered.
struct YamlRecordReader {
  const std::string& path;
  const std::string& name;
  const YAML::Node& node;
  void RequireScalars() const {
    struct Scalars {
      std::vector<std::string> keys;
      void Scalar(const char* key, EstimateField, const double&) { keys.emplace_back(key); }
      void Interval(const char*, const double&, const double&) {}
    } scalars;
    const ParameterEstimate none;
    VisitEstimateRecord(scalars, none);
    for (const auto& key : scalars.keys) {
      if (!node[key]) {
        throw InputError(fmt::format("{}: {}: needs a {}", Where(path, node), name, fmt::join(scalars.keys, " and a ")));
      }
    }
  }
  void Scalar(const char* key, EstimateField field, double& v) const {
    const std::string where = name + "." + key;
    v = field == EstimateField::kValue ? ParseNumber(path, where, node[key]) : ParseStandardError(path, where, node[key]);
  }
  void Interval(const char* key, double& low, double& high) const {
    const YAML::Node interval = node[key];
    if (!interval || !interval.IsSequence() || interval.size() != 2) return;
    low = ParseNumber(path, name + "." + key, interval[0]);
    high = ParseNumber(path, name + "." + key, interval[1]);
    if (low > high) {
      throw InputError(fmt::format("{}: {}.{} = [{}, {}]: the low end lies above the high end", Where(path, interval), name,
                                   key, low, high));
    }
  }
};



void ParseElbows(const std::string& path, const std::string&, const YAML::Node& value, PlanarRobotSection& robot,
                 ParameterFile&) {
  if (!value.IsSequence() || value.size() != 3) {
    throw InputError(fmt::format("{}: planar_robot.elbow: expected [e1, e2, e3] with each +1 or -1", Where(path, value)));
  }
  std::array<int, 3> elbow{};
  for (std::size_t i = 0; i < 3; ++i) {
    const double e = ParseNumber(path, "planar_robot.elbow", value[i]);
    if (e != 1.0 && e != -1.0) {
      throw InputError(fmt::format("{}: planar_robot.elbow: each entry must be +1 or -1, got {}", Where(path, value[i]), e));
    }
    elbow[i] = static_cast<int>(e);
  }
  robot.elbow = elbow;
}

std::string FormatElbows(const PlanarRobotSection& robot, const ParameterFile&) {
  const auto e = robot.elbow.value_or(std::array<int, 3>{1, 1, 1});
  return fmt::format("{:<28} # {}\n", fmt::format("  elbow: [{}, {}, {}]", e[0], e[1], e[2]),
                     "+1: B_i counter-clockwise of the ray A_i -> C");
}

void ParseAxisKey(const std::string& path, const std::string&, const YAML::Node& value, AxisSection& axis,
                  ParameterFile&) {
  if (value.IsNull()) return;
  const std::string text = value.IsScalar() ? value.Scalar() : "";
  if (text != "true" && text != "false") {
    throw InputError(fmt::format("{}: axis.linear: expected true (q in m, forces in N) or false (rotary)",
                                 Where(path, value)));
  }
  axis.linear = text == "true";
}

std::string FormatAxisKeys(const AxisSection& axis, const ParameterFile&) {
  if (!axis.linear) return "";
  return fmt::format("{:<28} # {}\n", "  linear: true", "q in m, forces in N, inertia in kg (docs/models.md#axis)");
}

void ParseControlKey(const std::string& path, const std::string&, const YAML::Node& value, CDriveSection&,
                     ParameterFile& file) {
  if (!value.IsNull()) file.Set(ParseControl(path, value));
}

std::string FormatControl(const CDriveSection&, const ParameterFile& file) {
  const auto* control = file.Find<CDriveControlSection>();
  if (control == nullptr) return "";
  std::string out = "  control:             # position controller and friction compensation, eq. (31)\n";
  if (control->law) {
    out += fmt::format("{:<28} # {}\n", fmt::format("    law: {}", ControlLawName(*control->law)),
                       "how K_I is read: PI, PD or PID");
  }
  return out + FormatSection(*control, CDriveControlParameterTable(), "    ");
}

void ParseFrequencyResponseKey(const std::string& path, const std::string& key, const YAML::Node& value,
                               FrequencyResponseSection& section, ParameterFile&) {
  if (key == "band_hz") {
    if (!value.IsSequence() || value.size() != 2) {
      throw InputError(fmt::format("{}: frf.band_hz: expected [low, high] in Hz", Where(path, value)));
    }
    const double low = ParseNumber(path, "frf.band_hz", value[0]), high = ParseNumber(path, "frf.band_hz", value[1]);
    if (!(low >= 0.0) || !(high >= low)) {
      throw InputError(fmt::format("{}: frf.band_hz: expected 0 <= low <= high, got [{}, {}]", Where(path, value), low,
                                   high));
    }
    section.band_hz = std::array<double, 2>{low, high};
  } else if (!value.IsNull()) {  // method
    if (!value.IsScalar()) throw InputError(fmt::format("{}: frf.method: expected text", Where(path, value)));
    section.method = value.Scalar();
  }
}

std::string FormatFrequencyResponseKeys(const FrequencyResponseSection& section, const ParameterFile&) {
  std::string out;
  if (section.band_hz) {
    out += fmt::format("{:<28} # {}\n", fmt::format("  band_hz: [{}, {}]", (*section.band_hz)[0], (*section.band_hz)[1]),
                       "coherent band used [Hz]");
  }
  if (section.method) out += fmt::format("  method: {}\n", Quoted(*section.method));
  return out;
}

// The registered model sections, in the order they are written: one line per model.
std::vector<SectionHandler>& Sections() {
  static std::vector<SectionHandler> sections = {
      MakeSection(DriveTrainParameterTable, "seed 000 section 4; docs/models.md#drive-train"),
      MakeSection(PlanarRobotParameterTable, "seed 000 sections 2, 5; docs/models.md#planar-robot", {"elbow"},
                  ParseElbows, FormatElbows),
      MakeSection(AxisParameterTable, "docs/models.md#axis: tau = J q'' + b q' + tau_c sgn(q') + tau_0", {"linear"},
                  ParseAxisKey, FormatAxisKeys,
                  [](const ParameterSpec& spec, const AxisSection& axis) { return AxisUnit(spec, axis.linear); }),
      MakeSection(CDriveParameterTable, "seed 001; docs/models.md#c-drive", {"control"}, ParseControlKey,
                  FormatControl),
      MakeSection(JointParameterTable, "docs/models.md#elastic-joint: two masses, link side"),
      MakeSection(FrequencyResponseTable, "docs/models.md#frequency-response: measured by drivetrain-fit frf",
                  {"band_hz", "method"}, ParseFrequencyResponseKey, FormatFrequencyResponseKeys),
      SerialRobotSectionHandler(),
      RobotCouplingSectionHandler(),
  };
  return sections;
}

}  // namespace

void RegisterParameterSection(SectionHandler handler) {
  for (const auto& section : Sections()) {
    if (section.name == handler.name) {
      throw std::logic_error("RegisterParameterSection: section '" + handler.name + "' exists already");
    }
  }
  Sections().push_back(std::move(handler));
}

namespace {

std::string SectionNames() {
  std::vector<std::string> names;
  for (const auto& section : Sections()) names.push_back(section.name);
  return fmt::format("{}", fmt::join(names, ", "));
}

}  // namespace

namespace {

// yaml-cpp parses nested collections recursively: refuse input that could
// exhaust the stack before handing it over (no real parameter file nests
// deeper than three levels).
void CheckNesting(const std::string& path, const std::string& text) {
  constexpr std::size_t kMaxBytes = 1 << 20;
  constexpr int kMaxFlowDepth = 32;
  constexpr std::size_t kMaxIndent = 64;
  if (text.size() > kMaxBytes) throw InputError(fmt::format("{}: parameter file larger than {} bytes", path, kMaxBytes));
  int depth = 0, line = 1;
  std::size_t indent = 0;
  bool at_line_start = true;
  for (char c : text) {
    if (c == '\n') {
      ++line;
      indent = 0;
      at_line_start = true;
      continue;
    }
    if (at_line_start && (c == ' ' || c == '-' || c == '\t')) {
      if (++indent > kMaxIndent) {
        throw InputError(fmt::format("{}:{}: nested deeper than a parameter file can be (indent over {})", path, line,
                                     kMaxIndent));
      }
      continue;
    }
    at_line_start = false;
    if (c == '[' || c == '{') {
      if (++depth > kMaxFlowDepth) {
        throw InputError(fmt::format("{}:{}: nested deeper than a parameter file can be (over {} brackets)", path,
                                     line, kMaxFlowDepth));
      }
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
}

}  // namespace

namespace {

// The feed-forward section (models/feedforward.h): units as strings, each
// gain {value, std}. Written by the tools; read back for `report`.
Feedforward ParseFeedforward(const std::string& path, const YAML::Node& node) {
  CheckMapping(path, "feedforward", node);
  Feedforward out;
  for (const auto& item : node) {
    const std::string key = item.first.Scalar();
    const std::string name = "feedforward." + key;
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
      throw InputError(fmt::format("{}: {}: unknown key (known: law, effort_unit, position_unit, {})",
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
  for (const auto& g : f.gains) {
    const std::string name = "feedforward." + g.key;
    out += fmt::format("  {}: {{value: {}, std: {}}}  # {}\n", g.key, Number(Writable(name, g.value)),
                       Short(Writable(name + ".std", g.standard_error)),
                       Comment(FeedforwardUnit(g.key, f.effort_unit, f.position_unit)));
  }
  return out;
}

}  // namespace

namespace {

// fit.correlation as written (FormatCorrelation): a row per estimate, or a
// list of [name, name, r] for many parameters. Read for propagating a
// derived value's std (e.g. feedback gains from Kv and Ka).
void ParseFitCorrelation(const std::string& path, const YAML::Node& node, ParameterFile& file) {
  if (!node) return;
  const auto value = [&](const YAML::Node& n) {
    const double r = ParseNumber(path, "fit.correlation", n);
    if (std::abs(r) > 1.0 + 1e-9) throw InputError(fmt::format("{}: fit.correlation: {} is outside [-1, 1]", Where(path, n), r));
    return r;
  };
  if (node.IsMap()) {
    std::vector<std::string> names;
    for (const auto& row : node) names.push_back(row.first.Scalar());
    for (const auto& row : node) {
      if (!row.second.IsSequence() || row.second.size() != names.size()) {
        throw InputError(fmt::format("{}: fit.correlation.{}: expected {} numbers", Where(path, row.second),
                                     row.first.Scalar(), names.size()));
      }
      for (std::size_t j = 0; j < names.size(); ++j) {
        file.fit_correlations.push_back({{row.first.Scalar(), names[j]}, value(row.second[j])});
      }
    }
  } else if (node.IsSequence()) {
    for (const auto& pair : node) {
      if (!pair.IsSequence() || pair.size() != 3 || !pair[0].IsScalar() || !pair[1].IsScalar()) {
        throw InputError(fmt::format("{}: fit.correlation: expected [name, name, r]", Where(path, pair)));
      }
      file.fit_correlations.push_back({{pair[0].Scalar(), pair[1].Scalar()}, value(pair[2])});
    }
  } else {
    throw InputError(fmt::format("{}: fit.correlation: expected rows or pairs", Where(path, node)));
  }
}

}  // namespace

namespace {

// The text of the top-level section `fit` as written: from the line of its
// key (at column 0) to the line of the next top-level key (the parser's
// marks, so that flow content at column 0 stays in), or to the end. "" when
// that text does not read back alone as the one section `fit` (e.g. a flow
// style document), and the section is then written anew or not at all.
std::string FitSectionText(const std::string& text, const YAML::Node& root) {
  int first = -1, next = -1;
  for (const auto& item : root) {
    const YAML::Mark mark = item.first.Mark();
    if (item.first.Scalar() == "fit") first = mark.column == 0 ? mark.line : -2;
  }
  if (first < 0) return "";
  for (const auto& item : root) {
    const int line = item.first.Mark().line;
    if (line > first && (next < 0 || line < next)) next = line;
    if (line == first && item.first.Scalar() != "fit") return "";
  }
  std::string block;
  int line = 0;
  for (std::size_t begin = 0; begin < text.size(); ++line) {
    const std::size_t end = std::min(text.find('\n', begin), text.size());
    if (line >= first && (next < 0 || line < next)) block.append(text, begin, end - begin).push_back('\n');
    begin = end + 1;
  }
  try {
    const YAML::Node alone = YAML::Load(block);
    if (!alone.IsMap() || alone.size() != 1 || !alone["fit"]) return "";
  } catch (const YAML::Exception&) {
    return "";
  }
  return block;
}

// The fit section of an earlier fit: its keys checked, its estimates and
// correlations read, its text kept.
void ParseFitSection(const std::string& path, const YAML::Node& node, ParameterFile& file) {
  // Provenance of an earlier fit: accepted so that a fit's output is a
  // valid input; replaced by a new fit, kept by a writer that fits nothing.
  CheckMapping(path, "fit", node);
  std::vector<std::string> known;
  for (const FitKey key : kFitSectionKeys) known.emplace_back(FitKeyName(key));
  for (const auto& entry : node) {
    const std::string key = entry.first.Scalar();
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      throw InputError(fmt::format("{}: fit.{}: unknown key (the fit section is written by the tools; known: {})",
                                   Where(path, entry.first), key, fmt::join(known, ", ")));
    }
  }
  file.had_fit_section = true;
  const YAML::Node data = node[FitKeyName(FitKey::kData)];
  if (data && data.IsSequence()) {
    for (const auto& record : data) {
      CheckKeys(path, "fit.data", record, {kFitDataKeys.begin(), kFitDataKeys.end()});
    }
  }
  const YAML::Node derived = node[FitKeyName(FitKey::kDerived)];
  if (derived && derived.IsMap()) {
    for (const auto& entry : derived) {
      CheckKeys(path, "fit.derived." + entry.first.Scalar(), entry.second, {kFitDerivedKeys.begin(), kFitDerivedKeys.end()});
    }
  }
  const YAML::Node estimates = node[FitKeyName(FitKey::kEstimates)];
  if (estimates && estimates.IsMap()) {
    for (const auto& entry : estimates) {
      const YAML::Node& e = entry.second;
      const std::string name = "fit.estimates." + entry.first.Scalar();
      CheckKeys(path, name, e, EstimateRecordKeys());
      ParameterEstimate estimate;
      estimate.name = entry.first.Scalar();
      YamlRecordReader reader{path, name, e};
      reader.RequireScalars();
      VisitEstimateRecord(reader, estimate);
      file.fit_estimates.push_back(estimate);
    }
  }
  ParseFitCorrelation(path, node[FitKeyName(FitKey::kCorrelation)], file);
  for (auto [key, into] : {std::pair{FitKeyName(FitKey::kRmse), &file.fit_rmse},
                           std::pair{FitKeyName(FitKey::kInflation), &file.fit_inflation}}) {
    const YAML::Node channels = node[key];
    if (!channels || !channels.IsMap()) continue;
    for (const auto& entry : channels) {
      // Read for a design's noise only: a value that is no number is left out.
      if (!entry.first.IsScalar() || !entry.second.IsScalar()) continue;
      try {
        into->emplace_back(entry.first.Scalar(), ParseNumber(path, "fit." + std::string(key), entry.second));
      } catch (const InputError&) {
      }
    }
  }
}

}  // namespace

ParameterFile ParseParameterFile(const std::string& path, const std::string& text) {
  CheckNesting(path, text);
  // YAML::Load reads the first document only: refuse a second one, marked by
  // a line "---" (or "...") after content. (YAML::LoadAll can loop on
  // hostile input, so the markers are found here.)
  {
    bool content = false;
    int line = 0;
    for (std::size_t begin = 0; begin < text.size();) {
      const std::size_t end = std::min(text.find('\n', begin), text.size());
      const std::string_view row(text.data() + begin, end - begin);
      ++line;
      const bool marker = (row.rfind("---", 0) == 0 || row.rfind("...", 0) == 0) &&
                          (row.size() == 3 || row[3] == ' ' || row[3] == '\t' || row[3] == '\r');
      if (marker && content) {
        throw InputError(fmt::format("{}:{}: a second YAML document: a parameter file holds one", path, line));
      }
      const std::size_t first = row.find_first_not_of(" \t\r");
      if (!marker && first != std::string_view::npos && row[first] != '#') content = true;
      begin = end + 1;
    }
  }
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(fmt::format("{}:{}:{}: invalid YAML: {}", path, e.mark.line + 1, e.mark.column + 1, e.msg));
  } catch (const YAML::Exception& e) {
    throw InputError(fmt::format("{}: invalid YAML: {}", path, e.msg));
  }
  if (root.IsNull()) throw InputError(fmt::format("{}: empty parameter file", path));
  CheckMapping(path, "parameter file", root);
  ParameterFile file;
  for (const auto& item : root) {
    const std::string section = item.first.Scalar();
    const SectionHandler* handler = nullptr;
    for (const auto& candidate : Sections()) {
      if (candidate.name == section) handler = &candidate;
    }
    if (handler != nullptr) {
      handler->parse(path, item.second, file);
    } else if (section == "feedforward") {
      file.feedforward = ParseFeedforward(path, item.second);
    } else if (section == "feedback") {
      file.feedback = ParseFeedbackSection(path, item.second);
    } else if (section == "fit") {
      ParseFitSection(path, item.second, file);
    } else {
      throw InputError(fmt::format("{}: {}: unknown section (known: {}, feedforward, feedback, fit)", Where(path, item.first), section,
                                   SectionNames()));
    }
  }
  if (file.had_fit_section) file.fit_text = FitSectionText(text, root);
  bool any_model = false;
  for (const auto& section : Sections()) any_model = any_model || section.present(file);
  if (!any_model && file.feedback.empty()) throw InputError(fmt::format("{}: no model section ({})", path, SectionNames()));
  return file;
}

ParameterFile ReadParameterFile(const std::string& path) {
  ReadLimits limits;
  limits.max_bytes = kMaxParameterFileBytes;
  limits.max_line_bytes = kMaxParameterLineBytes;
  limits.max_bytes_hint = "a parameter file may be at most 1 MiB";
  return ParseParameterFile(path, ReadFileToString(path, limits));
}

namespace {

// The fit section's data records.
std::string FormatDataRecords(const FitProvenance& provenance) {
  std::string out;
  for (const auto& record : provenance.data) {
    out += fmt::format("    - {{file: {}, sha256: {}, samples: {}", Quoted(record.file), record.sha256,
                       record.samples);
    if (!record.segment.empty()) out += fmt::format(", segment: {}", Quoted(record.segment));
    if (!record.notes.empty()) {
      std::vector<std::string> quoted;
      for (const auto& note : record.notes) quoted.push_back(Quoted(Abbreviated(note, kMaxProvenanceText / 4)));
      out += fmt::format(", notes: [{}]", fmt::join(quoted, ", "));
    }
    out += "}\n";
  }
  return out;
}

// The correlation matrix, or its strongest pairs for many parameters.
std::string FormatCorrelation(const FitResult* fit) {
  std::string out;
  const std::size_t p = fit->estimates.size();
  if (p <= kFullCorrelationParameters) {
    out += "\n";
    for (std::size_t i = 0; i < p; ++i) {
      out += fmt::format("    {}: [", fit->estimates[i].name);
      for (std::size_t j = 0; j < p; ++j) out += fmt::format("{}{:.4f}", j ? ", " : "", fit->correlation[i * p + j]);
      out += "]\n";
    }
  } else {
    // The matrix grows with the square of the parameters (a fit of 1000
    // logs with offsets: 8 MB): the strongest pairs (the matrix: --json).
    out += fmt::format("  # {} parameters: the {} strongest pairs (docs/formats.md)\n", p, kFullCorrelationParameters);
    for (const auto& pair : StrongestCorrelations(*fit, kFullCorrelationParameters)) {
      out += fmt::format("    - [{}, {}, {:.4f}]\n", fit->estimates[pair.first].name, fit->estimates[pair.second].name,
                         pair.correlation);
    }
  }
  return out;
}

// One key of the fit section (core/fit_section.h), its lines indented
// under "fit:"; model and derived only when there are any.
std::string FormatFitKey(FitKey key, const FitResult& fit, const FitProvenance& provenance,
                         const std::vector<DerivedQuantity>& derived) {
  const std::string name = FitKeyName(key);
  std::string out;
  switch (key) {
    case FitKey::kCommand:
      return fmt::format("  {}: {}\n", name, Quoted(Abbreviated(provenance.command, kMaxProvenanceText)));
    case FitKey::kVersion:
      return fmt::format("  {}: {}\n", name, Quoted(provenance.version));
    case FitKey::kModel:
      return provenance.model.empty() ? "" : fmt::format("  {}: {}\n", name, provenance.model);
    case FitKey::kData:
      return "  " + name + ":\n" + FormatDataRecords(provenance);
    case FitKey::kEstimates:
      out = "  " + name + ":\n";
      for (const auto& e : fit.estimates) {
        for (double v : {e.value, e.standard_error, e.ci95_low, e.ci95_high}) {
          if (!std::isfinite(v)) {
            throw OutputError(fmt::format("fit.estimates.{}: not finite ({} +- {}); nothing written", e.name, e.value,
                                          e.standard_error));
          }
        }
        YamlRecordWriter writer{"fit.estimates." + e.name, ""};
        VisitEstimateRecord(writer, e);
        out += fmt::format("    {}: {}{}\n", e.name, writer.Close(), e.unit.empty() ? "" : "  # " + Comment(e.unit));
      }
      return out;
    case FitKey::kDerived:
      if (derived.empty()) return "";
      out = "  " + name + ":\n";
      for (const auto& d : derived) {
        out += fmt::format("    {}: {{value: {}, std: {}}}  # {}\n", d.name,
                           Number(Writable("fit.derived." + d.name, d.value)),
                           Short(Writable("fit.derived." + d.name + ".std", d.standard_error)), Comment(d.unit));
      }
      return out;
    case FitKey::kCorrelation:
      return "  " + name + ":" + FormatCorrelation(&fit);
    case FitKey::kRmse:
      out = "  " + name + ":\n";
      for (const auto& c : fit.channels) out += fmt::format("    {}: {}\n", Quoted(c.name), Short(c.rmse));
      return out;
    case FitKey::kFitPercent:
      out = "  " + name + ":\n";
      for (const auto& c : fit.channels) {
        out += std::isnan(c.fit_percent)
                   ? fmt::format("    {}: null  # the channel (nearly) does not vary: docs/models.md#adequacy\n",
                                 Quoted(c.name))
                   : fmt::format("    {}: {:.3f}\n", Quoted(c.name), c.fit_percent);
      }
      return out;
    case FitKey::kAutocorrelation:
      out = "  " + name + ":  # residual lag-1, per channel\n";
      for (const auto& c : fit.channels) out += fmt::format("    {}: {:.4f}\n", Quoted(c.name), c.autocorrelation);
      return out;
    case FitKey::kInflation:
      out = "  " + name + ":  # std with / without the correlation of the residuals (docs/models.md#identification)\n";
      for (const auto& c : fit.channels) out += fmt::format("    {}: {:.4f}\n", Quoted(c.name), c.inflation);
      return out;
    case FitKey::kSingularValues:
      out = "  " + name + ": [";
      for (std::size_t i = 0; i < fit.singular_values.size(); ++i) {
        out += fmt::format("{}{:.4g}", i ? ", " : "", fit.singular_values[i]);
      }
      return out + "]\n";
    case FitKey::kIterations:
      return fmt::format("  {}: {}\n", name, fit.iterations);
    case FitKey::kConverged:
      return fmt::format("  {}: {}\n", name, fit.converged ? "true" : "false");
  }
  return out;
}

// What ReadParameterFile accepts (1 MiB, lines of 64 KiB): else nothing is written.
void RequireReadable(const std::string& out) {
  if (out.size() > kMaxParameterFileBytes) {
    throw OutputError(fmt::format("the parameter file would be {} bytes, a parameter file holds at most {}; nothing "
                                  "written",
                                  out.size(), kMaxParameterFileBytes));
  }
  for (std::size_t begin = 0, line = 1; begin < out.size(); ++line) {
    const std::size_t end = std::min(out.find('\n', begin), out.size());
    if (end - begin > kMaxParameterLineBytes) {
      throw OutputError(fmt::format("line {} of the parameter file would be {} bytes (\"{}...\"), at most {}; nothing "
                                    "written",
                                    line, end - begin, out.substr(begin, 40), kMaxParameterLineBytes));
    }
    begin = end + 1;
  }
}

}  // namespace

std::string FormatParameterFile(const ParameterFile& file, const FitResult* fit, const FitProvenance* provenance,
                                const std::vector<DerivedQuantity>& derived) {
  std::string out = "# driveid parameter file (docs/formats.md). Units: SI, radians.\n";
  for (const auto& section : Sections()) {
    if (section.present(file)) out += section.format(file);
  }
  if (!file.feedforward.gains.empty()) out += FormatFeedforward(file.feedforward);
  if (!file.feedback.empty()) out += FormatFeedbackSection(file.feedback);
  if (fit == nullptr && provenance == nullptr) out += file.fit_text;
  if (fit != nullptr && provenance != nullptr) {
    out += "fit:\n";
    for (const FitKey key : kFitSectionKeys) out += FormatFitKey(key, *fit, *provenance, derived);
  }
  RequireReadable(out);
  return out;
}

}  // namespace driveid
