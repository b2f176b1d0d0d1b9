// The axis's section (models/axis.h) and whether it is linear.
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

}  // namespace

DRIVEID_PARAMETER_SECTION(axis_section) {
  return MakeSection(AxisParameterTable, "docs/models.md#axis: tau = J q'' + b q' + tau_c sgn(q') + tau_0", {"linear"},
                     ParseAxisKey, FormatAxisKeys,
                     [](const ParameterSpec& spec, const AxisSection& axis) { return AxisUnit(spec, axis.linear); });
}

}  // namespace driveid
