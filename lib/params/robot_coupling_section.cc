#include "params/robot_coupling_section.h"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>
#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "core/errors.h"
#include "params/parameter_file.h"
#include "models/serial_dynamics.h"

namespace driveid {
namespace {

using section_io::CheckMapping;
using section_io::Number;
using section_io::ParseNumber;
using section_io::ParseText;
using section_io::Where;
using section_io::YamlName;

constexpr std::size_t kMaxCoupled = 64;

RobotCouplingSection ParseCoupling(const std::string& path, const YAML::Node& node) {
  CheckMapping(path, "robot.coupling", node);
  RobotCouplingSection s;
  for (const auto& item : node) {
    const std::string key = item.first.Scalar();
    if (key == "joints") {
      if (!item.second.IsSequence() || item.second.size() > kMaxCoupled) {
        throw InputError(fmt::format("{}: robot.coupling.joints: a list of at most {} joint names", Where(path, item.second), kMaxCoupled));
      }
      for (std::size_t i = 0; i < item.second.size(); ++i) {
        s.joints.push_back(ParseText(path, fmt::format("robot.coupling.joints[{}]", i), item.second[i]));
      }
    } else if (key == "matrix") {
      const YAML::Node& rows = item.second;
      if (!rows.IsSequence() || rows.size() > kMaxCoupled) {
        throw InputError(fmt::format("{}: robot.coupling.matrix: a list of rows", Where(path, rows)));
      }
      for (std::size_t r = 0; r < rows.size(); ++r) {
        if (!rows[r].IsSequence() || rows[r].size() > kMaxCoupled) {
          throw InputError(fmt::format("{}: robot.coupling.matrix[{}]: a list of numbers", Where(path, rows[r]), r));
        }
        std::vector<double> row;
        for (std::size_t c = 0; c < rows[r].size(); ++c) {
          row.push_back(ParseNumber(path, fmt::format("robot.coupling.matrix[{}][{}]", r, c), rows[r][c]));
        }
        s.matrix.push_back(std::move(row));
      }
    } else {
      throw InputError(fmt::format("{}: robot.coupling.{}: unknown key (known: joints, matrix)", Where(path, item.first), key));
    }
  }
  bool square = !s.joints.empty() && s.matrix.size() == s.joints.size();
  for (const auto& row : s.matrix) square = square && row.size() == s.joints.size();
  if (!square) {
    throw InputError(fmt::format("{}: robot.coupling: needs joints and a square matrix over them ({} joints, {} rows)",
                                 Where(path, node), s.joints.size(), s.matrix.size()));
  }
  return s;
}

void Parse(const std::string& path, const YAML::Node& node, ParameterFile& file) {
  CheckMapping(path, "robot", node);
  RobotCouplingSection s;
  for (const auto& item : node) {
    const std::string key = item.first.Scalar();
    if (key != "coupling") {
      throw InputError(fmt::format("{}: robot.{}: unknown key (known: coupling)", Where(path, item.first), key));
    }
    s = ParseCoupling(path, item.second);
  }
  if (s.joints.empty()) throw InputError(fmt::format("{}: robot: needs coupling", Where(path, node)));
  file.Set(std::move(s));
}

std::string Format(const ParameterFile& file) {
  const RobotCouplingSection& s = *file.Find<RobotCouplingSection>();
  std::string out = "robot:  # docs/formats.md#the-robot-section\n  coupling:  # motor angles = matrix q (docs/models.md#coupled-drives)\n";
  std::vector<std::string> names;
  for (const std::string& j : s.joints) names.push_back(YamlName(j));
  out += fmt::format("    joints: [{}]\n    matrix: [", fmt::join(names, ", "));
  for (std::size_t r = 0; r < s.matrix.size(); ++r) {
    std::vector<std::string> row;
    for (double v : s.matrix[r]) row.push_back(Number(v));
    out += fmt::format("{}[{}]", r ? ", " : "", fmt::join(row, ", "));
  }
  return out + "]\n";
}

}  // namespace

SerialRobot WithCoupling(SerialRobot robot, const ParameterFile& file, const std::string& path) {
  const RobotCouplingSection* s = file.Find<RobotCouplingSection>();
  if (s == nullptr) return robot;
  for (const SerialJoint& j : robot.joints) {
    if (j.mimic >= 0) {
      throw InputError(fmt::format("{}: robot.coupling with a mimic joint ('{}'): coupled drives of a robot with mimic "
                                   "joints are not supported",
                                   path, j.name));
    }
  }
  std::vector<std::size_t> coupled;
  for (const std::string& name : s->joints) {
    const auto it = std::find_if(robot.joints.begin(), robot.joints.end(), [&](const SerialJoint& j) { return j.name == name; });
    if (it == robot.joints.end()) {
      throw InputError(fmt::format("{}: robot.coupling: the URDF has no movable joint '{}'", path, name));
    }
    const auto index = static_cast<std::size_t>(it - robot.joints.begin());
    if (std::find(coupled.begin(), coupled.end(), index) != coupled.end()) {
      throw InputError(fmt::format("{}: robot.coupling: joint '{}' named twice", path, name));
    }
    coupled.push_back(index);
  }
  const auto k = static_cast<Eigen::Index>(coupled.size());
  Eigen::MatrixXd block(k, k);
  for (Eigen::Index r = 0; r < k; ++r) {
    for (Eigen::Index c = 0; c < k; ++c) block(r, c) = s->matrix[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)];
  }
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(block);
  if (!lu.isInvertible() || !(std::abs(lu.determinant()) > 1e-12 * std::pow(block.cwiseAbs().maxCoeff(), static_cast<double>(k)))) {
    throw InputError(fmt::format("{}: robot.coupling: the matrix is singular: every motor angle must follow from the "
                                 "joints' and back", path));
  }
  robot.coupling = SerialCouplingMatrix(robot.size(), coupled, block);
  return robot;
}

SectionHandler RobotCouplingSectionHandler() {
  return {RobotCouplingSection::kSectionName,
          [](const ParameterFile& file) { return file.Find<RobotCouplingSection>() != nullptr; }, Parse, Format};
}

// A serial arm's joint coupling (mimic joints, coupled wrists).
DRIVEID_PARAMETER_SECTION(robot_coupling_section) { return RobotCouplingSectionHandler(); }

}  // namespace driveid
