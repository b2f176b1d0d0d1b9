// The parameter file's `robot` section (docs/formats.md#the-robot-section):
// what a serial robot has that its URDF does not say — the coupling of its
// drives (docs/models.md#coupled-drives), motor angles = R q over the named
// joints:
//   robot:
//     coupling:
//       joints: [wrist_2, wrist_3]
//       matrix: [[1, 0], [-0.5, 1]]   # a row per motor, a column per joint above
// Given to `robot --urdf` with --params, written into its output, and read
// with the fit wherever the arm is predicted (validate, design, export).
#pragma once

#include <string>
#include <vector>

#include "params/parameter_file.h"
#include "params/parameter_sections.h"
#include "models/serial_robot.h"

namespace driveid {

struct RobotCouplingSection {
  static constexpr const char* kSectionName = "robot";
  std::vector<std::string> joints;           ///< the coupled joints
  std::vector<std::vector<double>> matrix;   ///< k x k, rows: motors
};

/// The robot with the file's coupling (none without a robot section).
/// InputError naming `path` for a joint the robot lacks or named twice, or
/// a matrix that is not square over the joints, finite and invertible.
SerialRobot WithCoupling(SerialRobot robot, const ParameterFile& file, const std::string& path);

/// Its reader and writer (registered in params/parameter_file.cc).
SectionHandler RobotCouplingSectionHandler();

}  // namespace driveid
