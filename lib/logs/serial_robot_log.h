// Logs of a serial robot (docs/formats.md#serial-robot-logs): the time and,
// per movable joint of its URDF that mimics none (models/serial_dynamics.h
// SerialCoordinates: a mimic joint follows its leader), q_<joint> (or q<k>, k from 1 in the
// robot's order), optionally qd_<joint> (or qd<k>) and tau_<joint> (or
// tau<k>) [rad, rad/s, N m; m, m/s, N for a prismatic joint].
#pragma once

#include <string>
#include <vector>

#include "logs/csv_log.h"
#include "models/serial_robot.h"

namespace driveid {

/// A log of every coordinate joint (robot order): positions [rad or m],
/// rates where logged (empty per joint otherwise) and torques [N m or N].
struct SerialRobotLog {
  std::string path;
  std::vector<double> time;
  std::vector<std::vector<double>> position, rate, torque;
};

/// The logical columns ReadLogs asks for (logs/log_input.h): t, then per joint
/// "q_<name>|q<k>", "?qd_<name>|qd<k>", "tau_<name>|tau<k>".
std::vector<std::string> SerialRobotLogColumns(const SerialRobot& robot);

/// The log from columns read with SerialRobotLogColumns(robot).
SerialRobotLog MakeSerialRobotLog(const SerialRobot& robot, CsvLog csv);

}  // namespace driveid
