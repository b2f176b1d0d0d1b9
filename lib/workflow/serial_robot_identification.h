// A serial robot's identification as `drivetrain-fit robot --urdf` runs it
// (docs/models.md#serial-robot): the base-parameter fit of all logs, the
// parameter file's serial_robot section, per-joint statistics, the torque
// trace and its plot (measured vs model and residuals per joint). The
// command reads the URDF and the logs, calls this, emits.
#pragma once

#include <string>
#include <vector>

#include "fit/robot/consistent_parameters.h"
#include "fit/robot/serial_robot_fit.h"
#include "params/serial_robot_section.h"
#include "robot_description/urdf_robot.h"
#include "report/plot.h"

namespace driveid {

/// A half window chosen from the logs spans this many of their steps: the
/// differentiator needs 2 samples on each side (signal/local_polynomial.h),
/// also in the processing refit at half the window (fit/robot/serial_robot_fit.h).
inline constexpr double kSerialWindowSteps = 5.0;

struct SerialRobotIdentificationOptions {
  SerialRobotFitOptions fit;
  /// The URDF prior's weight in the consistent fit, relative to one std of
  /// the data (docs/models.md#physical-consistency).
  double prior_weight = kConsistentPriorWeight;
  /// Joints whose viscous friction is fitted per direction (SerialJoint::
  /// viscous_per_direction), by name, or "all".
  std::vector<std::string> viscous_per_direction;
  bool trace = false;  ///< fill the trace CSV's rows
  /// The window was not given: fit.half_window is the least, raised to
  /// kSerialWindowSteps steps of the slowest log (a 30 Hz bag), with a note.
  bool window_from_logs = false;
  /// Every bound on these fields (‹field› names the option); see core/option_check.h.
  bool IsValid(std::string* error) const;
};

struct SerialRobotIdentification {
  SerialRobotFitOutput result;  ///< its estimates the consistent ones (intervals moved with them)
  ConsistentParameters consistent;
  SerialRobotSection section;  ///< for the parameter file
  std::string summary;         ///< per joint and per base parameter, as text
  std::string trace_csv;       ///< per log, time and joint: measured and model torque
  std::vector<PlotPanel> panels;
};

/// `urdf_path` and `urdf_sha256` are recorded in the section. OptionError
/// for a joint name in ‹per_direction› the robot has not.
SerialRobotIdentification IdentifySerialRobot(const UrdfRobot& urdf, const std::string& urdf_path,
                                              const std::string& urdf_sha256, const std::vector<SerialRobotLog>& logs,
                                              const SerialRobotIdentificationOptions& options);

}  // namespace driveid
