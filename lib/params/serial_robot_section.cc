#include "params/serial_robot_section.h"

#include <algorithm>
#include <cctype>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <yaml-cpp/yaml.h>

#include "core/errors.h"
#include "models/serial_drive_term.h"
#include "params/parameter_file.h"
#include "system/sha256.h"
#include "robot_description/urdf_robot.h"

namespace driveid {
namespace {

using section_io::CheckMapping;
using section_io::Number;
using section_io::ParseNumber;
using section_io::Where;
using section_io::Writable;

std::string Key(const std::string& name) { return section_io::YamlName(name); }

std::string Text(const std::string& path, const std::string& name, const YAML::Node& node) {
  return section_io::ParseText(path, name, node);
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

std::vector<SerialBodyEntry> ParseBodies(const std::string& path, const YAML::Node& node) {
  if (!node.IsSequence()) throw InputError(fmt::format("{}: serial_robot.bodies: expected a list", Where(path, node)));
  std::vector<SerialBodyEntry> out;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string name = fmt::format("serial_robot.bodies[{}]", i);
    CheckMapping(path, name, node[i]);
    SerialBodyEntry e;
    std::size_t found = 0;
    for (const auto& item : node[i]) {
      const std::string key = item.first.Scalar();
      if (key == "link") {
        e.link = Text(path, name + ".link", item.second);
        continue;
      }
      const auto& names = InertialParameterNames();
      const auto at = std::find(names.begin(), names.end(), key);
      if (at == names.end()) {
        throw InputError(fmt::format("{}: {}.{}: unknown key (known: link, m, mx, my, mz, Ixx, Ixy, Ixz, Iyy, Iyz, Izz)",
                                     Where(path, item.first), name, key));
      }
      e.parameters[static_cast<std::size_t>(at - names.begin())] = ParseNumber(path, name + "." + key, item.second);
      ++found;
    }
    if (e.link.empty() || found != kInertialParameters) {
      throw InputError(fmt::format("{}: {}: needs link and all 10 parameters", Where(path, node[i]), name));
    }
    out.push_back(e);
  }
  return out;
}

// The drive terms' keys, those every joint has first ("armature, viscous,
// coulomb and offset"), for messages.
std::string DriveKeys(bool only_always) {
  std::vector<std::string> keys;
  for (const SerialDriveTerm* term : SerialDriveTerms()) {
    if (term->always() || !only_always) keys.emplace_back(term->key());
  }
  if (only_always && keys.size() > 1) return fmt::format("{} and {}", fmt::join(keys.begin(), keys.end() - 1, ", "), keys.back());
  return fmt::format("{}", fmt::join(keys, ", "));
}

std::vector<SerialDriveEntry> ParseDrives(const std::string& path, const YAML::Node& node) {
  if (!node.IsSequence()) throw InputError(fmt::format("{}: serial_robot.drives: expected a list", Where(path, node)));
  const std::vector<const SerialDriveTerm*>& terms = SerialDriveTerms();
  const auto always = static_cast<std::size_t>(
      std::count_if(terms.begin(), terms.end(), [](const SerialDriveTerm* t) { return t->always(); }));
  std::vector<SerialDriveEntry> out;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string name = fmt::format("serial_robot.drives[{}]", i);
    CheckMapping(path, name, node[i]);
    SerialDriveEntry e;
    std::size_t found = 0;
    for (const auto& item : node[i]) {
      const std::string key = item.first.Scalar();
      if (key == "joint") {
        e.joint = Text(path, name + ".joint", item.second);
        continue;
      }
      const auto term = std::find_if(terms.begin(), terms.end(), [&](const SerialDriveTerm* t) { return key == t->key(); });
      if (term == terms.end()) {
        throw InputError(fmt::format("{}: {}.{}: unknown key (known: joint, {})", Where(path, item.first), name, key,
                                     DriveKeys(false)));
      }
      e.drive.*((*term)->member()) = ParseNumber(path, name + "." + key, item.second);
      if ((*term)->always()) {
        ++found;
      } else {
        if (std::find(e.asked.begin(), e.asked.end(), key) == e.asked.end()) e.asked.push_back(key);
      }
    }
    if (e.joint.empty() || found != always) {
      throw InputError(fmt::format("{}: {}: needs joint, {}", Where(path, node[i]), name, DriveKeys(true)));
    }
    out.push_back(e);
  }
  return out;
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
    } else if (key == "bodies") {
      s.bodies = ParseBodies(path, item.second);
    } else if (key == "drives") {
      s.drives = ParseDrives(path, item.second);
    } else if (key == "base") {
      if (!item.second.IsSequence()) {
        throw InputError(fmt::format("{}: serial_robot.base: expected a list", Where(path, item.second)));
      }
      for (std::size_t i = 0; i < item.second.size(); ++i) s.base.push_back(ParseEntry(path, item.second[i], i));
    } else {
      throw InputError(fmt::format("{}: serial_robot.{}: unknown key (known: urdf, urdf_sha256, half_window, base, bodies, drives)",
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
  if (!s.bodies.empty()) {
    out += "  bodies:  # physically consistent (docs/models.md#physical-consistency), in each body's frame\n";
    for (const SerialBodyEntry& b : s.bodies) {
      out += fmt::format("    - {{link: {}", Key(b.link));
      for (std::size_t k = 0; k < kInertialParameters; ++k) {
        out += fmt::format(", {}: {}", InertialParameterNames()[k],
                           Number(Writable("serial_robot.bodies." + std::string(InertialParameterNames()[k]),
                                           b.parameters[k])));
      }
      out += "}\n";
    }
  }
  if (!s.drives.empty()) {
    out += "  drives:\n";
    for (const SerialDriveEntry& d : s.drives) {
      out += fmt::format("    - {{joint: {}", Key(d.joint));
      for (const SerialDriveTerm* term : SerialDriveTerms()) {
        if (!term->always() && std::find(d.asked.begin(), d.asked.end(), term->key()) == d.asked.end()) continue;
        out += fmt::format(", {}: {}", term->key(),
                           Number(Writable(std::string("serial_robot.drives.") + term->key(), d.drive.*(term->member()))));
      }
      out += "}\n";
    }
  }
  return out;
}

}  // namespace

SectionUrdf ReadSectionUrdf(const SerialRobotSection& section, const std::string& given, const std::string& params_path) {
  SectionUrdf out;
  out.path = given.empty() ? section.urdf : given;
  out.text = ReadUrdfText(out.path);
  if (!section.urdf_sha256.empty() && Sha256Hex(out.text) != section.urdf_sha256) {
    throw InputError(fmt::format("{}: its SHA-256 differs from the one {} was fitted with ({}): another URDF", out.path,
                                 params_path, section.urdf_sha256));
  }
  out.robot = ParseUrdfRobot(out.path, out.text).robot;
  for (const SerialDriveEntry& d : section.drives) {
    if (d.asked.empty()) continue;
    const auto joint = std::find_if(out.robot.joints.begin(), out.robot.joints.end(),
                                    [&](const SerialJoint& j) { return j.name == d.joint; });
    if (joint == out.robot.joints.end()) {
      throw InputError(fmt::format("{}: serial_robot.drives names joint '{}', which {} has not", params_path, d.joint,
                                   out.path));
    }
    for (const SerialDriveTerm* term : SerialDriveTerms()) {
      if (std::find(d.asked.begin(), d.asked.end(), term->key()) != d.asked.end()) term->Ask(*joint);
    }
  }
  return out;
}

SectionHandler SerialRobotSectionHandler() {
  return {SerialRobotSection::kSectionName,
          [](const ParameterFile& file) { return file.Find<SerialRobotSection>() != nullptr; }, Parse, Format};
}

// A serial arm (models/serial_robot.h): its URDF and what was identified.
DRIVEID_PARAMETER_SECTION(serial_robot_section) { return SerialRobotSectionHandler(); }

}  // namespace driveid
