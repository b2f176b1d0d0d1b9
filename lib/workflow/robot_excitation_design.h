// `drivetrain-fit design robot` (docs/models.md#serial-robot-excitation):
// the prior (a robot --urdf fit's consistent bodies and drives, or the
// URDF's inertials with no friction), the torque noise per joint (given, or
// the prior fit's residual rmse times its inflation), the design
// (design/robot_excitation.h), and the trajectory CSV, plot panels and text
// the command writes.
#pragma once

#include <string>
#include <vector>

#include "design/robot_excitation.h"
#include "params/parameter_file.h"
#include "models/serial_robot.h"
#include "workflow/excitation_design.h"

namespace driveid {

struct RobotDesignRequest {
  const ParameterFile* prior = nullptr;  ///< a robot --urdf fit, or null (the URDF's inertials)
  std::string params_path;               ///< its path, for messages
  std::vector<double> noise;             ///< [N m or N]: one for every joint, or one per joint; empty: the prior fit's
  bool csv = false, plot = false;
  std::string command_line;
  /// Every noise value finite and > 0 (‹noise›).
  bool IsValid(std::string* error) const;
};

/// The design of `robot` (the URDF's, the prior's structure). OptionError
/// (‹noise›) when no noise is given and the prior has none per joint.
ExcitationDesignRun DesignRobotRun(const SerialRobot& robot, const RobotDesignOptions& design,
                                   const RobotDesignRequest& request);

}  // namespace driveid
