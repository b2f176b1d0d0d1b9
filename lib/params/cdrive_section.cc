// The C-drive's section (models/cdrive.h) and its controller (control/cdrive_control_settings.h).
#include <array>
#include <string>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "core/errors.h"
#include "params/parameter_file.h"
#include "params/parameter_sections.h"

namespace driveid {
namespace {

using namespace section_io;

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

}  // namespace

DRIVEID_PARAMETER_SECTION(cdrive_section) {
  return MakeSection(CDriveParameterTable, "seed 001; docs/models.md#c-drive", {"control"}, ParseControlKey,
                     FormatControl);
}

}  // namespace driveid
