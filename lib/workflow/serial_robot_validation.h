// `drivetrain-fit validate ARM.yaml LOG...` of a serial robot
// (docs/models.md#serial-robot-validation): every joint's torque predicted
// from the parameter file alone — its serial_robot section's base
// parameters on the structure of the URDF it names — one validated channel
// per joint and log, with fit %, RMSE and relative error.
#pragma once

#include <string>
#include <vector>

#include "logs/serial_robot_log.h"
#include "params/serial_robot_section.h"
#include "models/serial_robot.h"
#include "workflow/validation_run.h"

namespace driveid {

/// Throws InputError naming `path` when the section's base parameters are
/// not the URDF's (another robot, an edited URDF).
ValidationRun RunSerialRobotValidation(const std::vector<SerialRobotLog>& logs, const SerialRobotSection& section,
                                       const SerialRobot& robot, const std::string& path);

/// The MJCF's hinge and slide joints as a robot's joints (names only: what
/// a log's columns need), in the model's order.
SerialRobot MjcfJoints(const std::string& mjcf);
/// The differentiator's half window [s] a robot --urdf fit uses by default.
double DefaultSerialHalfWindow();

/// The same from an MJCF in MuJoCo (sim/mujoco_inverse.h): `joints` names
/// the MJCF's joints (the logs' columns), the logs differentiated as a fit
/// with half window `half_window` [s] does.
ValidationRun RunMujocoSerialValidation(const std::vector<SerialRobotLog>& logs, const std::string& mjcf,
                                        const SerialRobot& joints, double half_window);

}  // namespace driveid
