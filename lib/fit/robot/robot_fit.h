// Identification of the planar robot's rigid-body model (docs/models.md#planar-robot) from joint
// angles and motor currents along a trajectory. The actuator equations
//   Theta theta'' + n_g^2 d_g theta' + G+ m_c x'' = n_g tau_motor,m
// are multiplied by G, which removes the unknown null-space prestress
// (G tau_null = 0) and the minimum-norm split:
//   n_g G (k_t i) = Theta G theta'' + d_g n_g^2 G theta' + m_c x''   (2 rows per sample)
// linear in Theta, m_c, d_g, solved jointly over all samples and logs by the
// fit core. Rates and accelerations of the joint angles come from the
// zero-phase local-polynomial differentiator; x from forward kinematics of
// the smoothed angles, differentiated the same way.
// The prediction splits the minimum-norm motor current into the parts of
// seed 000 Fig. 7: inertia (Theta G' x'' + G+ m_c x''), centrifugal/Coriolis
// (Theta dG' x') and friction (n_g^2 d_g theta'), each divided by n_g k_t.
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

#include "fit/core/least_squares.h"
#include "models/planar_robot.h"
#include "logs/robot_log.h"

namespace driveid {


struct RobotFitOptions {
  std::vector<std::string> free = FitParameterKeys(PlanarRobotParameterTable(), "robot", true);
  double half_window = 0.005;  ///< differentiator half window [s]
  FitOptions fit;
  /// Whether the values can be used; else `error` names the field and the constraint.
  bool IsValid(std::string* error) const;
};

/// Current prediction along one log, per motor (Fig. 7).
struct RobotCurrentPrediction {
  std::vector<double> time;
  std::array<std::vector<double>, 3> measured;          ///< i as logged [A]
  std::array<std::vector<double>, 3> measured_motion;   ///< its minimum-norm part G+ G i [A]
  std::array<std::vector<double>, 3> inertia, coriolis, friction, total;  ///< model parts [A]
};

struct RobotFitOutput {
  PlanarRobotParameters params;
  FitResult fit;
  std::vector<RobotCurrentPrediction> predictions;
};

RobotFitOutput FitRobot(const std::vector<RobotLog>& logs, const PlanarRobotParameters& start,
                        const RobotFitOptions& options);

}  // namespace driveid
