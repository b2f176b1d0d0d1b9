// A serial robot (models/serial_robot.h) from a URDF (docs/formats.md#urdf),
// parsed by Debian's liburdfdom: revolute, continuous and prismatic joints
// become the robot's joints, in a tree from the root link; links carried by
// fixed joints merge into the body that moves them (their inertials added in
// its frame); links fixed to the root do not move and are left out (noted).
// A <mimic> joint follows its leader, q = multiplier q_leader + offset
// (SerialJoint::mimic; a mimic of a mimic resolved to the first leader).
// Floating and planar joints are refused by name.
// Meshes, visuals and collisions are ignored.
#pragma once

#include <string>
#include <vector>

#include "models/serial_robot.h"

namespace driveid {

struct UrdfRobot {
  SerialRobot robot;
  /// Per joint: its <dynamics damping friction> as viscous and Coulomb
  /// friction (zero where absent), the prior of the drives' fit.
  std::vector<SerialDriveParameters> drives;
  std::vector<std::string> notes;  ///< merged and left-out links
};

/// Parses the URDF text read from `path` (named in errors). Throws
/// InputError naming the file and what is wrong.
UrdfRobot ParseUrdfRobot(const std::string& path, const std::string& text);

/// A URDF file's text (at most 64 MiB; InputError naming the file).
std::string ReadUrdfText(const std::string& path);
/// Reads and parses a URDF file.
UrdfRobot ReadUrdfRobot(const std::string& path);

}  // namespace driveid
