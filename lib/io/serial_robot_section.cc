#include "io/serial_robot_section.h"

#include <cctype>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "core/errors.h"
#include "io/parameter_file.h"

namespace driveid {
namespace {

using section_io::CheckMapping;
using section_io::Number;
using section_io::ParseNumber;
using section_io::Where;
using section_io::Writable;

// Names of columns are the URDF's link and joint names with a prefix: no
// quoting needed for letters, digits, '_', '-', '.'; anything else quoted.
std::string Key(const std::string& name) {
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

std::string Text(const std::string& path, const std::string& name, const YAML::Node& node) {
  if (!node.IsScalar()) throw InputError(fmt::format("{}: {}: expected text", Where(path, node), name));
  return node.Scalar();
}

SerialBaseEntry ParseEntry(const std::string& path, const YAML::Node& node, std::size_t index) {
  const std::string name = fmt::format("serial_robot.base[{}]", index);
  CheckMapping(path, name, node);
  SerialBaseEntry e;
  bool has_value = false;
  for (const auto& item : node) {
    const std::string key = item.first.Scalar();
    if (key == "lead") {
      e.lead = Text(path, name + ".lead", item.second);
    } else if (key == "value") {
      e.value = ParseNumber(path, name + ".value", item.second);
      has_value = true;
    } else if (key == "combination") {
      CheckMapping(path, name + ".combination", item.second);
      for (const auto& term : item.second) {
        e.combination.emplace_back(term.first.Scalar(),
                                   ParseNumber(path, name + ".combination." + term.first.Scalar(), term.second));
      }
    } else {
      throw InputError(fmt::format("{}: {}.{}: unknown key (known: lead, combination, value)", Where(path, item.first),
                                   name, key));
    }
  }
  if (e.lead.empty() || !has_value || e.combination.empty() || e.combination.front().first != e.lead) {
    throw InputError(fmt::format("{}: {}: needs lead, a combination that starts with the lead, and value",
                                 Where(path, node), name));
  }
  return e;
}

void Parse(const std::string& path, const YAML::Node& node, ParameterFile& file) {
  CheckMapping(path, "serial_robot", node);
  SerialRobotSection s;
  for (const auto& item : node) {
    const std::string key = item.first.Scalar();
    if (key == "urdf") {
      s.urdf = Text(path, "serial_robot.urdf", item.second);
    } else if (key == "urdf_sha256") {
      s.urdf_sha256 = Text(path, "serial_robot.urdf_sha256", item.second);
    } else if (key == "half_window") {
      s.half_window = ParseNumber(path, "serial_robot.half_window", item.second);
      if (!(s.half_window > 0.0)) {
        throw InputError(fmt::format("{}: serial_robot.half_window: must be > 0 s", Where(path, item.second)));
      }
    } else if (key == "base") {
      if (!item.second.IsSequence()) {
        throw InputError(fmt::format("{}: serial_robot.base: expected a list", Where(path, item.second)));
      }
      for (std::size_t i = 0; i < item.second.size(); ++i) s.base.push_back(ParseEntry(path, item.second[i], i));
    } else {
      throw InputError(fmt::format("{}: serial_robot.{}: unknown key (known: urdf, urdf_sha256, half_window, base)",
                                   Where(path, item.first), key));
    }
  }
  if (s.urdf.empty() || s.base.empty() || !(s.half_window > 0.0)) {
    throw InputError(fmt::format("{}: serial_robot: needs urdf, half_window and base (written by drivetrain-fit robot "
                                 "‹urdf›)",
                                 Where(path, node)));
  }
  file.Set(std::move(s));
}

std::string Format(const ParameterFile& file) {
  const SerialRobotSection& s = *file.Find<SerialRobotSection>();
  std::string out = "serial_robot:  # docs/models.md#serial-robot: base parameters of the URDF's robot\n";
  out += fmt::format("  urdf: {}\n", Key(s.urdf));
  if (!s.urdf_sha256.empty()) out += fmt::format("  urdf_sha256: {}\n", s.urdf_sha256);
  out += fmt::format("  half_window: {}\n", Number(Writable("serial_robot.half_window", s.half_window)));
  out += "  base:\n";
  for (const SerialBaseEntry& e : s.base) {
    out += fmt::format("    - lead: {}\n      combination: {{", Key(e.lead));
    for (std::size_t i = 0; i < e.combination.size(); ++i) {
      out += fmt::format("{}{}: {}", i > 0 ? ", " : "", Key(e.combination[i].first),
                         Number(Writable("serial_robot.base.combination", e.combination[i].second)));
    }
    out += fmt::format("}}\n      value: {}\n", Number(Writable("serial_robot.base.value", e.value)));
  }
  return out;
}

}  // namespace

SectionHandler SerialRobotSectionHandler() {
  return {SerialRobotSection::kSectionName,
          [](const ParameterFile& file) { return file.Find<SerialRobotSection>() != nullptr; }, Parse, Format};
}

}  // namespace driveid
