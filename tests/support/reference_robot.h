// Independent generator of planar-robot logs for tests (docs/models.md#planar-robot, 5.5): its
// own inverse kinematics, joint rates and accelerations by central
// differences of the inverse kinematics along the path, the transposed
// inverse Jacobian G from numerical derivatives of the inverse kinematics
// (dtheta/dx = G'), and the rigid-body currents with a null-space prestress.
// Nothing here uses the library's kinematics or simulator.
#pragma once

#include <array>
#include <vector>

namespace reference {

struct RobotLog {
  std::vector<double> t;
  std::array<std::vector<double>, 3> theta, current;
};

struct Robot {
  double a = 1.0, l = 0.488, n_g = 80, Theta = 0.55, m_c = 0.5, d_g = 0.002, k_t = 0.5;
};

/// 250 mm triangle, 50 m/s^2, 3 m/s, `dwell` at the corners, `loops` loops, 1 kHz,
/// 13-bit encoders behind the gears, prestress [N m at the output], current noise [A].
RobotLog SimulateTriangle(const Robot& r, int loops, double dwell, double prestress, double noise, unsigned seed);

}  // namespace reference
