// The serial arm a command works on, built in one place for `robot --urdf`,
// `validate`, `design robot` and the Python module (which runs those
// commands): the URDF with the drives' coupling of a parameter file's
// robot_coupling section (params/robot_coupling_section.h).
#pragma once

#include <optional>
#include <string>

#include "params/parameter_file.h"
#include "params/robot_coupling_section.h"
#include "robot_description/urdf_robot.h"

namespace driveid {

/// The arm to identify: the URDF at `urdf_path` (its text kept for its
/// SHA-256), with the coupling of `params_path` when one is given
/// (OptionError when that file has no coupling section).
struct RobotToIdentify {
  std::string urdf_text;
  UrdfRobot robot;
  std::optional<RobotCouplingSection> coupling;
};
RobotToIdentify ReadRobotToIdentify(const std::string& urdf_path, const std::string& params_path);

/// The arm a fitted parameter file describes: its serial_robot section's
/// URDF (or `urdf_path` when given, checked against the section's SHA-256)
/// with the file's coupling; InputError when the file has no serial_robot
/// section.
SerialRobot RobotOfParameterFile(const ParameterFile& file, const std::string& params_path,
                                 const std::string& urdf_path);

}  // namespace driveid
