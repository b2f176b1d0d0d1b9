// The planar robot's section (models/planar_robot.h) and its elbows.
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

}  // namespace

DRIVEID_PARAMETER_SECTION(planar_robot_section) {
  return MakeSection(PlanarRobotParameterTable, "seed 000 sections 2, 5; docs/models.md#planar-robot", {"elbow"},
                     ParseElbows, FormatElbows);
}

}  // namespace driveid
