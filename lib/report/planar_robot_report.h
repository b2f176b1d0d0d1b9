// Report of the planar robot model at a pose: joint angles, G, the Cartesian
// mass matrix M = Theta G G' + m_c 1 and C = Theta G dG' + n_g^2 d_g G G'
// (docs/models.md#planar-robot), the null-space direction, and the seed-000 values beside.
#pragma once

#include <string>

#include "models/planar_robot.h"
#include "report/json.h"

namespace driveid {

/// Text report. Throws std::domain_error if the pose is out of reach.
std::string FormatPlanarRobotReport(const PlanarRobotParameters& robot, const Vector2& pose, const Vector2& velocity,
                                    const std::string& source);

/// The same quantities as a JSON object.
Json PlanarRobotReportJson(const PlanarRobotParameters& robot, const Vector2& pose, const Vector2& velocity,
                           const std::string& source);

}  // namespace driveid
