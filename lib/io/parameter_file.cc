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

/// Declaration of one scalar key: doc, unit, minimum and whether it may be absent.
struct ScalarKey {
  const char* key;
  double DriveTrainParameters::*member;
  const char* doc;
  double minimum;
  bool minimum_exclusive;
  bool required;
};

constexpr double kNoMinimum = -std::numeric_limits<double>::infinity();

const ScalarKey kDriveTrainKeys[] = {
    {"n_g", &DriveTrainParameters::gear_ratio, "gear ratio [-]", 0.0, true, true},
    {"k_Tl", &DriveTrainParameters::link_stiffness, "link bending stiffness [N m/rad]", 0.0, true, true},
    {"k_Tg", &DriveTrainParameters::gearbox_stiffness, "gearbox stiffness [N m/rad]", 0.0, true, true},
    {"Theta_motor", &DriveTrainParameters::motor_inertia, "motor rotor inertia, motor side [kg m^2]", 0.0, true, true},
    {"Theta_g", &DriveTrainParameters::gearbox_inertia, "gearbox inertia, motor side [kg m^2]", 0.0, false, false},
    {"d_g", &DriveTrainParameters::viscous_friction, "gearbox viscous friction at the gear input [N m s/rad]", 0.0, false, true},
    {"tau_c", &DriveTrainParameters::coulomb_friction, "Coulomb friction at the gear output [N m]", 0.0, false, true},
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

// Keys of a mapping, refusing duplicates and non-scalar keys.
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

DriveTrainParameters ParseDriveTrain(const std::string& path, const YAML::Node& section) {
  CheckMapping(path, "drivetrain", section);
  DriveTrainParameters params;
  params.gearbox_inertia = 0.0;  // optional: only the full model needs it
  std::set<std::string> given;
  for (const auto& item : section) {
    const std::string key = item.first.Scalar();
    const ScalarKey* spec = nullptr;
    for (const auto& candidate : kDriveTrainKeys) {
      if (key == candidate.key) spec = &candidate;
    }
    if (spec == nullptr) {
      std::string known;
      for (const auto& candidate : kDriveTrainKeys) known += std::string(known.empty() ? "" : ", ") + candidate.key;
      throw InputError(fmt::format("{}: drivetrain.{}: unknown key (known: {})", Where(path, item.first), key, known));
    }
    if (item.second.IsNull()) continue;  // "key: " with no value = not given
    const std::string name = "drivetrain." + key;
    const double value = ParseNumber(path, name, item.second);
    if (spec->minimum_exclusive ? !(value > spec->minimum) : !(value >= spec->minimum)) {
      throw InputError(fmt::format("{}: {}: must be {} {}, got {} ({})", Where(path, item.second), name,
                                   spec->minimum_exclusive ? ">" : ">=", spec->minimum, value, spec->doc));
    }
    params.*(spec->member) = value;
    given.insert(key);
  }
  for (const auto& spec : kDriveTrainKeys) {
    if (spec.required && !given.count(spec.key)) {
      throw InputError(fmt::format("{}: drivetrain.{}: missing value ({})", Where(path, section), spec.key, spec.doc));
    }
  }
  return params;
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

}  // namespace

ParameterFile ParseParameterFile(const std::string& path, const std::string& text) {
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
    } else if (section == "fit") {
      // Provenance of an earlier fit: accepted so that a fit's output is a
      // valid input, and replaced when a new file is written.
      CheckMapping(path, "fit", item.second);
      file.had_fit_section = true;
    } else {
      throw InputError(fmt::format("{}: {}: section not supported by this version of driveid",
                                   Where(path, item.first), section));
    }
  }
  return file;
}

ParameterFile ReadParameterFile(const std::string& path) { return ParseParameterFile(path, ReadFileToString(path)); }

std::string FormatParameterFile(const ParameterFile& file, const FitResult* fit, const FitProvenance* provenance) {
  std::string out = "# driveid parameter file (SPEC section 4). Units: SI, radians.\n";
  if (file.drivetrain) {
    out += "drivetrain:            # seed 000 section 4, SPEC 5.1\n";
    for (const auto& spec : kDriveTrainKeys) {
      const std::string line = fmt::format("  {}: {}", spec.key, Number((*file.drivetrain).*(spec.member)));
      out += fmt::format("{:<28} # {}\n", line, spec.doc);
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
