// The planar robot's rigid-body fit as `drivetrain-fit robot` runs it
// (docs/models.md#planar-robot): the fit of all logs, the current
// prediction split as in seed 000 Fig. 7 for the trace, and its plot. The
// command parses, loads the logs, calls this, emits.
#pragma once

#include <string>
#include <vector>

#include "core/fit_result.h"
#include "fit/robot/robot_fit.h"
#include "logs/robot_log.h"
#include "models/planar_robot.h"
#include "report/plot.h"

namespace driveid {

struct RobotIdentificationOptions {
  RobotFitOptions fit;
  bool trace = false;  ///< fill the trace CSV's rows
  /// Every bound on these fields (‹field› names the option); see core/option_check.h.
  bool IsValid(std::string* error) const;
};

struct RobotIdentification {
  PlanarRobotParameters params;  ///< the start values with the estimates put in
  FitResult fit;
  std::string trace_csv;         ///< per log, time and motor: measured, motion part, model and its split
  std::vector<PlotPanel> panels; ///< motor 1 of the first log as in Fig. 7, then the residuals of all motors
};

/// Fits `logs` from `start`. Throws as FitRobot.
RobotIdentification IdentifyRobot(const std::vector<RobotLog>& logs, const PlanarRobotParameters& start,
                                  const RobotIdentificationOptions& options);

}  // namespace driveid
