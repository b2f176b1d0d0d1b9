// Report of the planar robot model at a pose: joint angles, G, the Cartesian
// mass matrix M = Theta G G' + m_c 1 and C = Theta G dG' + n_g^2 d_g G G'
// (docs/models.md#planar-robot), the null-space direction, and the seed-000 values beside.
#pragma once

#include <string>

#include "models/planar_robot.h"
#include "report/json.h"

namespace driveid {

/// The robot model at one pose.
struct PlanarRobotReport {
  std::string source;
  PlanarRobotParameters robot;
  Vector2 pose, velocity;  ///< centre joint [m], [m/s]
  Vector3 theta;           ///< joint angles [rad]
  Matrix23 g;              ///< G [1/m]
  Matrix2 m;               ///< Cartesian mass matrix [kg]
  Matrix2 c;               ///< Cartesian damping [N s/m]
  Vector3 n;               ///< null space of G (prestress direction)
};

/// Throws std::domain_error if the pose is out of reach.
PlanarRobotReport CalcPlanarRobotReport(const PlanarRobotParameters& robot, const Vector2& pose,
                                        const Vector2& velocity, const std::string& source);
std::string FormatPlanarRobotReport(const PlanarRobotReport& report);
Json PlanarRobotReportJson(const PlanarRobotReport& report);

}  // namespace driveid
