#include "io/parameter_file.h"

#include <charconv>
#include <cmath>
#include <limits>
#include <set>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "core/errors.h"
#include "io/csv_log.h"

namespace driveid {
namespace {

constexpr double kNotGiven = std::numeric_limits<double>::quiet_NaN();

/// Declaration of one scalar key of a section: doc with unit, minimum, and
/// whether the section is incomplete without it.
template <typename T>
struct ScalarKey {
  const char* key;
  double T::*member;
  const char* doc;
  double minimum;
  bool minimum_exclusive;
  bool required;
};

const ScalarKey<DriveTrainParameters> kDriveTrainKeys[] = {
    {"n_g", &DriveTrainParameters::gear_ratio, "gear ratio [-]", 0.0, true, true},
    {"k_Tl", &DriveTrainParameters::link_stiffness, "link bending stiffness [N m/rad]", 0.0, true, true},
    {"k_Tg", &DriveTrainParameters::gearbox_stiffness, "gearbox stiffness [N m/rad]", 0.0, true, true},
    {"Theta_motor", &DriveTrainParameters::motor_inertia, "motor rotor inertia, motor side [kg m^2]", 0.0, true, true},
    {"Theta_g", &DriveTrainParameters::gearbox_inertia, "gearbox inertia, motor side [kg m^2]", 0.0, false, false},
    {"d_g", &DriveTrainParameters::viscous_friction, "gearbox viscous friction at the gear input [N m s/rad]", 0.0, false, true},
    {"tau_c", &DriveTrainParameters::coulomb_friction, "Coulomb friction at the gear output [N m]", 0.0, false, true},
};

const ScalarKey<CDriveParameters> kCDriveKeys[] = {
    {"p", &CDriveParameters::lead, "screw lead [m]", 0.0, true, true},
    {"I_h", &CDriveParameters::hub_inertia, "motor rotor + coupling + screw inertia [kg m^2]", 0.0, false, false},
    {"I_c", &CDriveParameters::collar_inertia, "collar inertia about the screw axis [kg m^2]", 0.0, false, false},
    {"m", &CDriveParameters::collar_mass, "collar mass [kg]", 0.0, false, false},
    {"beta", &CDriveParameters::viscous_motor, "viscous, rotor and bearings [N m s/rad]", 0.0, false, false},
    {"gamma", &CDriveParameters::viscous_collar, "viscous, collar on the screws [N m s/rad]", 0.0, false, false},
    {"delta", &CDriveParameters::coulomb_motor, "Coulomb, rotor and bearings [N m]", 0.0, false, false},
    {"eta", &CDriveParameters::coulomb_collar, "Coulomb, collar on the screws [N m]", 0.0, false, false},
};

const ScalarKey<AxisSection> kAxisKeys[] = {
    {"inertia", &AxisSection::inertia, "J, inertia [kg m^2] (linear axis: mass [kg])", 0.0, false, false},
    {"viscous", &AxisSection::viscous, "b, viscous friction [N m s/rad] (linear: N s/m)", 0.0, false, false},
    {"coulomb", &AxisSection::coulomb, "tau_c, Coulomb friction [N m] (linear: N)", 0.0, false, false},
    {"offset", &AxisSection::offset, "tau_0, constant offset [N m] (linear: N)", -std::numeric_limits<double>::infinity(), false, false},
    {"k_t", &AxisSection::torque_constant, "torque constant for logs of current [N m/A]", 0.0, true, false},
    {"n_g", &AxisSection::gear_ratio, "gear ratio, to report d_g = b / n_g^2 [-]", 0.0, true, false},
};

const ScalarKey<PlanarRobotParameters> kRobotKeys[] = {
    {"base_distance", &PlanarRobotParameters::base_distance, "a, distance of the base joints [m]", 0.0, true, true},
    {"l", &PlanarRobotParameters::link_length, "link length [m]", 0.0, true, true},
    {"n_g", &PlanarRobotParameters::gear_ratio, "gear ratio [-]", 0.0, true, true},
    {"Theta", &PlanarRobotParameters::output_inertia, "actuator inertia at the gear output [kg m^2]", 0.0, false, true},
    {"m_c", &PlanarRobotParameters::center_mass, "mass of the centre joint [kg]", 0.0, false, true},
    {"d_g", &PlanarRobotParameters::viscous_friction, "gearbox viscous friction at the gear input [N m s/rad]", 0.0, false, true},
    {"k_t", &PlanarRobotParameters::torque_constant, "motor torque constant [N m/A]", 0.0, true, true},
};

const ScalarKey<CDriveControlSettings> kControlKeys[] = {
    {"K_P", &CDriveControlSettings::proportional_gain, "proportional gain [N m/rad]", 0.0, false, true},
    {"K_I", &CDriveControlSettings::second_gain, "second gain as printed: integral [N m/(rad s)] (PI, PID) or derivative [N m s/rad] (PD)", 0.0, false, true},
    {"K_D", &CDriveControlSettings::derivative_gain, "derivative gain, PID only [N m s/rad]", 0.0, false, false},
    {"dead_zone", &CDriveControlSettings::dead_zone, "dead zone on velocities and their difference [rad/s]", 0.0, false, false},
    {"rate_limit", &CDriveControlSettings::rate_limit, "rate limit of each unit Coulomb term [1/s]", 0.0, true, false},
    {"velocity_window", &CDriveControlSettings::velocity_window, "encoder velocity difference window [s]", 0.0, true, false},
    {"sample_time", &CDriveControlSettings::sample_time, "controller period [s]", 0.0, true, false},
    {"encoder_counts", &CDriveControlSettings::encoder_counts, "encoder counts per revolution", 0.0, true, false},
};

const char* const kKnownSections[] = {"drivetrain", "axis", "planar_robot", "cdrive", "fit"};

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

template <typename T, std::size_t N>
std::string KnownKeys(const ScalarKey<T> (&keys)[N], const std::vector<std::string>& extra) {
  std::string known;
  for (const auto& key : keys) known += std::string(known.empty() ? "" : ", ") + key.key;
  for (const auto& key : extra) known += ", " + key;
  return known;
}

// Parses the scalar keys of a section into `out`. Keys in `extra` are left
// to the caller (returned as nodes); every other key must be declared.
template <typename T, std::size_t N>
std::vector<std::pair<std::string, YAML::Node>> ParseScalars(const std::string& path, const std::string& section,
                                                             const YAML::Node& node, const ScalarKey<T> (&keys)[N],
                                                             const std::vector<std::string>& extra, T& out) {
  CheckMapping(path, section, node);
  std::vector<std::pair<std::string, YAML::Node>> others;
  std::set<std::string> given;
  for (const auto& item : node) {
    const std::string key = item.first.Scalar();
    const ScalarKey<T>* spec = nullptr;
    for (const auto& candidate : keys) {
      if (key == candidate.key) spec = &candidate;
    }
    if (spec == nullptr) {
      bool is_extra = false;
      for (const auto& name : extra) is_extra = is_extra || key == name;
      if (!is_extra) {
        throw InputError(fmt::format("{}: {}.{}: unknown key (known: {})", Where(path, item.first), section, key,
                                     KnownKeys(keys, extra)));
      }
      others.emplace_back(key, item.second);
      continue;
    }
    if (item.second.IsNull()) continue;  // "key: " with no value = not given
    const std::string name = section + "." + key;
    const double value = ParseNumber(path, name, item.second);
    if (spec->minimum_exclusive ? !(value > spec->minimum) : !(value >= spec->minimum)) {
      throw InputError(fmt::format("{}: {}: must be {} {}, got {} ({})", Where(path, item.second), name,
                                   spec->minimum_exclusive ? ">" : ">=", spec->minimum, value, spec->doc));
    }
    out.*(spec->member) = value;
    given.insert(key);
  }
  for (const auto& spec : keys) {
    if (spec.required && !given.count(spec.key)) {
      throw InputError(fmt::format("{}: {}.{}: missing value ({})", Where(path, node), section, spec.key, spec.doc));
    }
  }
  return others;
}

DriveTrainParameters ParseDriveTrain(const std::string& path, const YAML::Node& node) {
  DriveTrainParameters params;
  params.gearbox_inertia = 0.0;  // optional: only the full model needs it
  ParseScalars(path, "drivetrain", node, kDriveTrainKeys, {}, params);
  return params;
}

CDriveControlSettings ParseControl(const std::string& path, const YAML::Node& node) {
  CDriveControlSettings control;
  const auto others = ParseScalars(path, "cdrive.control", node, kControlKeys, {"law"}, control);
  for (const auto& [key, value] : others) {
    const std::string law = value.IsScalar() ? value.Scalar() : "";
    if (law == "PI") control.law = ControlLaw::kPI;
    else if (law == "PD") control.law = ControlLaw::kPD;
    else if (law == "PID") control.law = ControlLaw::kPID;
    else throw InputError(fmt::format("{}: cdrive.control.law: must be PI, PD or PID", Where(path, value)));
  }
  return control;
}

CDriveSection ParseCDrive(const std::string& path, const YAML::Node& node) {
  CDriveSection section;
  CDriveParameters& p = section.params;
  p.hub_inertia = p.collar_inertia = p.collar_mass = kNotGiven;
  p.viscous_motor = p.viscous_collar = p.coulomb_motor = p.coulomb_collar = kNotGiven;
  const auto others = ParseScalars(path, "cdrive", node, kCDriveKeys, {"k_t", "control"}, p);
  for (const auto& [key, value] : others) {
    if (key == "k_t") {
      if (value.IsNull()) continue;
      section.torque_constant = ParseNumber(path, "cdrive.k_t", value);
      if (!(section.torque_constant > 0.0)) {
        throw InputError(fmt::format("{}: cdrive.k_t: must be > 0, got {} (motor torque constant [N m/A])",
                                     Where(path, value), section.torque_constant));
      }
    } else if (!value.IsNull()) {
      section.control = ParseControl(path, value);
    }
  }
  return section;
}

std::string Quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (u < 0x20) {
      out += fmt::format("\\x{:02x}", u);
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string Number(double value) { return fmt::format("{}", value); }
std::string Short(double value) { return fmt::format("{:.6g}", value); }

template <typename T, std::size_t N>
std::string FormatScalars(const T& values, const ScalarKey<T> (&keys)[N], const std::string& indent) {
  std::string out;
  for (const auto& spec : keys) {
    const double value = values.*(spec.member);
    if (!IsGiven(value)) continue;
    const std::string line = fmt::format("{}{}: {}", indent, spec.key, Number(value));
    out += fmt::format("{:<28} # {}\n", line, spec.doc);
  }
  return out;
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

ParameterFile ParseParameterFile(const std::string& path, const std::string& text) {
  CheckNesting(path, text);
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
    bool known = false;
    for (const char* name : kKnownSections) known = known || section == name;
    if (!known) {
      throw InputError(fmt::format("{}: {}: unknown section (known: drivetrain, axis, planar_robot, cdrive, fit)",
                                   Where(path, item.first), section));
    }
    if (section == "drivetrain") {
      file.drivetrain = ParseDriveTrain(path, item.second);
    } else if (section == "planar_robot") {
      PlanarRobotParameters robot;
      const auto others = ParseScalars(path, "planar_robot", item.second, kRobotKeys, {"elbow"}, robot);
      for (const auto& [key, value] : others) {
        if (!value.IsSequence() || value.size() != 3) {
          throw InputError(fmt::format("{}: planar_robot.elbow: expected [e1, e2, e3] with each +1 or -1", Where(path, value)));
        }
        for (std::size_t i = 0; i < 3; ++i) {
          const double e = ParseNumber(path, "planar_robot.elbow", value[i]);
          if (e != 1.0 && e != -1.0) {
            throw InputError(fmt::format("{}: planar_robot.elbow: each entry must be +1 or -1, got {}", Where(path, value[i]), e));
          }
          robot.elbow[i] = static_cast<int>(e);
        }
      }
      file.planar_robot = robot;
    } else if (section == "axis") {
      AxisSection axis;
      ParseScalars(path, "axis", item.second, kAxisKeys, {}, axis);
      file.axis = axis;
    } else if (section == "cdrive") {
      file.cdrive = ParseCDrive(path, item.second);
    } else if (section == "fit") {
      // Provenance of an earlier fit: accepted so that a fit's output is a
      // valid input, and replaced when a new file is written.
      CheckMapping(path, "fit", item.second);
      file.had_fit_section = true;
      const YAML::Node estimates = item.second["estimates"];
      if (estimates && estimates.IsMap()) {
        for (const auto& entry : estimates) {
          const YAML::Node& e = entry.second;
          if (!e.IsMap() || !e["value"] || !e["std"]) continue;
          const std::string name = "fit.estimates." + entry.first.Scalar();
          ParameterEstimate estimate;
          estimate.name = entry.first.Scalar();
          estimate.value = ParseNumber(path, name + ".value", e["value"]);
          estimate.standard_error = ParseNumber(path, name + ".std", e["std"]);
          const YAML::Node interval = e["ci95"];
          if (interval && interval.IsSequence() && interval.size() == 2) {
            estimate.ci95_low = ParseNumber(path, name + ".ci95", interval[0]);
            estimate.ci95_high = ParseNumber(path, name + ".ci95", interval[1]);
          }
          file.fit_estimates.push_back(estimate);
        }
      }
    } else {
      throw InputError(fmt::format("{}: {}: section not supported by this version of driveid",
                                   Where(path, item.first), section));
    }
  }
  if (!file.drivetrain && !file.axis && !file.planar_robot && !file.cdrive) {
    throw InputError(fmt::format("{}: no model section (drivetrain, axis, planar_robot or cdrive)", path));
  }
  return file;
}

ParameterFile ReadParameterFile(const std::string& path) { return ParseParameterFile(path, ReadFileToString(path)); }

std::string FormatParameterFile(const ParameterFile& file, const FitResult* fit, const FitProvenance* provenance,
                                const std::vector<DerivedQuantity>& derived) {
  std::string out = "# driveid parameter file (SPEC section 4). Units: SI, radians.\n";
  if (file.drivetrain) {
    out += "drivetrain:            # seed 000 section 4, SPEC 5.1\n";
    out += FormatScalars(*file.drivetrain, kDriveTrainKeys, "  ");
  }
  if (file.planar_robot) {
    out += "planar_robot:          # seed 000 sections 2, 5; SPEC 5.3\n";
    out += FormatScalars(*file.planar_robot, kRobotKeys, "  ");
    const auto& e = file.planar_robot->elbow;
    out += fmt::format("{:<28} # {}\n", fmt::format("  elbow: [{}, {}, {}]", e[0], e[1], e[2]),
                       "+1: B_i counter-clockwise of the ray A_i -> C");
  }
  if (file.axis) {
    // Every axis key is optional: an empty section must still read back as a mapping.
    const std::string body = FormatScalars(*file.axis, kAxisKeys, "  ");
    out += body.empty() ? "axis: {}               # SPEC 5.2: tau = J q'' + b q' + tau_c sgn(q') + tau_0\n"
                        : "axis:                  # SPEC 5.2: tau = J q'' + b q' + tau_c sgn(q') + tau_0\n" + body;
  }
  if (file.cdrive) {
    out += "cdrive:                # seed 001, SPEC 5.4\n";
    out += FormatScalars(file.cdrive->params, kCDriveKeys, "  ");
    if (IsGiven(file.cdrive->torque_constant)) {
      out += fmt::format("{:<28} # {}\n", fmt::format("  k_t: {}", Number(file.cdrive->torque_constant)),
                         "motor torque constant [N m/A]");
    }
    if (file.cdrive->control) {
      out += "  control:             # position controller and friction compensation, eq. (31)\n";
      out += fmt::format("{:<28} # {}\n", fmt::format("    law: {}", ControlLawName(file.cdrive->control->law)),
                         "how K_I is read: PI, PD or PID");
      out += FormatScalars(*file.cdrive->control, kControlKeys, "    ");
    }
  }
  if (fit != nullptr && provenance != nullptr) {
    out += "fit:\n";
    out += fmt::format("  command: {}\n", Quoted(provenance->command));
    out += fmt::format("  version: {}\n", Quoted(provenance->version));
    if (!provenance->model.empty()) out += fmt::format("  model: {}\n", provenance->model);
    out += "  data:\n";
    for (const auto& record : provenance->data) {
      out += fmt::format("    - {{file: {}, sha256: {}, samples: {}}}\n", Quoted(record.file), record.sha256,
                         record.samples);
    }
    out += "  estimates:\n";
    for (const auto& e : fit->estimates) {
      out += fmt::format("    {}: {{value: {}, std: {}, ci95: [{}, {}]}}\n", e.name, Number(e.value),
                         Short(e.standard_error), Short(e.ci95_low), Short(e.ci95_high));
    }
    if (!derived.empty()) {
      out += "  derived:\n";
      for (const auto& d : derived) {
        out += fmt::format("    {}: {{value: {}, std: {}}}  # {}\n", d.name, Number(d.value), Short(d.standard_error),
                           d.unit);
      }
    }
    const std::size_t p = fit->estimates.size();
    out += "  correlation:\n";
    for (std::size_t i = 0; i < p; ++i) {
      out += fmt::format("    {}: [", fit->estimates[i].name);
      for (std::size_t j = 0; j < p; ++j) out += fmt::format("{}{:.4f}", j ? ", " : "", fit->correlation[i * p + j]);
      out += "]\n";
    }
    out += "  rmse:\n";
    for (const auto& c : fit->channels) out += fmt::format("    {}: {}\n", Quoted(c.name), Short(c.rmse));
    out += "  fit_percent:\n";
    for (const auto& c : fit->channels) out += fmt::format("    {}: {:.3f}\n", Quoted(c.name), c.fit_percent);
    out += "  singular_values: [";
    for (std::size_t i = 0; i < fit->singular_values.size(); ++i) {
      out += fmt::format("{}{:.4g}", i ? ", " : "", fit->singular_values[i]);
    }
    out += "]\n";
    out += fmt::format("  iterations: {}\n", fit->iterations);
    out += fmt::format("  converged: {}\n", fit->converged ? "true" : "false");
  }
  return out;
}

}  // namespace driveid
