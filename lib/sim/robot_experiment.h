// Synthetic robot logs (docs/models.md#planar-robot, 5.5): the centre joint runs an
// equilateral triangle (side 250 mm, centred in the workspace) edge by edge,
// rest to rest, with a trapezoidal speed profile (50 m/s^2, 3 m/s), a dwell
// at each corner, for several loops. Joint angles from inverse kinematics,
// quantised by motor encoders behind the gears; motor currents from the
// rigid-body model (minimum-norm torques), plus a constant null-space
// prestress and Gaussian current noise.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "logs/robot_log.h"
#include "models/planar_robot.h"

namespace driveid {


struct RobotExperiment {
  double side = 0.25;            ///< triangle side [m]
  double acceleration = 50.0;    ///< [m/s^2]
  double speed = 3.0;            ///< [m/s]
  double dwell = 0.05;           ///< rest at each corner [s]
  int loops = 3;
  double rate = 1000.0;          ///< [Hz]
  double encoder_counts = 8192;  ///< per motor revolution (angles quantised by 2 pi / (counts n_g))
  double prestress = 3.0;        ///< null-space joint torque at the gear output [N m]
  double current_noise = 0.0;    ///< [A]
  std::uint64_t seed = 1;
};

/// Reference path sample: position, velocity, acceleration of the centre joint.
struct PathSample {
  Vector2 position, velocity, acceleration;
};
/// The triangle path as a function of time (holds the last corner after the end).
PathSample CalcTrianglePath(const PlanarRobotParameters& robot, const RobotExperiment& e, double time);
double CalcTriangleDuration(const RobotExperiment& e);

/// Throws OptionError for bad options, std::domain_error if the
/// triangle leaves the workspace.
RobotLog SimulateRobotExperiment(const PlanarRobotParameters& robot, const RobotExperiment& experiment);


}  // namespace driveid
