// Independent generator of C-drive logs for tests (docs/models.md#c-drive-5.5): the motors
// follow a Table II program exactly (4-5-6-7 polynomial forward over T, then
// back), torques from the inverse dynamics of (28) written here from the
// equations, angles quantised by 13-bit encoders, Gaussian torque noise.
#pragma once

#include <vector>

namespace reference {

struct CDrive {
  double p = 0.06, I_h = 6e-4, I_c = 1.6e-3, m = 2.0;
  double beta = 0.002655, gamma = 0.004333, delta = 0.1086, eta = 0.1501;
};

struct CDriveLog {
  std::vector<double> t, psi_L, psi_R, tau_L, tau_R;
};

/// `alpha_left`, `alpha_right` [rad]: Table II amplitudes; `stroke` T [s];
/// `cycles` forward-and-back cycles; sampled at `rate` Hz.
CDriveLog SimulateProgram(const CDrive& d, double alpha_left, double alpha_right, double stroke, int cycles,
                          double rate, double sigma, unsigned seed);

}  // namespace reference
