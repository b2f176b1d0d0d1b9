// The parameter file's `serial_robot` section (docs/formats.md#the-serial_robot-section):
// which URDF the robot's structure comes from (its path as given and its
// SHA-256), the differentiator's half window, and the identified base
// parameters (fit/core/base_parameters.h), each by its lead column, its
// combination of the URDF's parameters and its value. The values' std and
// intervals are the `fit` section's, under the lead column's name.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "params/parameter_file.h"
#include "params/parameter_sections.h"
#include "models/serial_robot.h"

namespace driveid {

struct SerialBaseEntry {
  std::string lead;                                         ///< the lead column's name
  std::vector<std::pair<std::string, double>> combination;  ///< (column, coefficient), lead first
  double value = 0.0;
};

/// A body's physically consistent inertial parameters (the 10 standard
/// ones in its frame, models/serial_robot.h), named by its link.
struct SerialBodyEntry {
  std::string link;
  InertialParameters parameters{};
};

/// A joint's drive as the consistent fit left it.
struct SerialDriveEntry {
  std::string joint;
  SerialDriveParameters drive;
  /// The keys of the drive terms not in every joint's model
  /// (SerialDriveTerm::always) that this joint was fitted with, which are
  /// written and read (`viscous_asymmetry`: SerialJoint::viscous_per_direction).
  std::vector<std::string> asked;
};

struct SerialRobotSection {
  static constexpr const char* kSectionName = "serial_robot";
  std::string urdf;         ///< as given on the command line
  std::string urdf_sha256;  ///< of its bytes
  double half_window = 0.0;
  std::vector<SerialBaseEntry> base;
  /// The consistent parameters (docs/models.md#physical-consistency): every
  /// body and drive, whose base combinations are the values above.
  std::vector<SerialBodyEntry> bodies;
  std::vector<SerialDriveEntry> drives;
};

/// The URDF a section was fitted on: `given` when not empty, else the path
/// the section names; its text and robot, its joints' viscous friction per
/// direction (each drive term) as the section's drives were fitted. InputError when its
/// SHA-256 is not the section's (naming both files).
struct SectionUrdf {
  std::string path, text;
  SerialRobot robot;
};
SectionUrdf ReadSectionUrdf(const SerialRobotSection& section, const std::string& given, const std::string& params_path);

/// Its reader and writer (registered in params/parameter_file.cc).
SectionHandler SerialRobotSectionHandler();

}  // namespace driveid
