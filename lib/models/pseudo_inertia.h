// Physical consistency of a body's inertial parameters (models/serial_robot.h,
// docs/models.md#physical-consistency). The parameters
// pi = (m, h, I) are those of a real mass distribution exactly when the
// pseudo-inertia
//   J = [[Sigma, h], [h^T, m]],  Sigma = tr(I)/2 1 - I  (the second moments),
// is positive semi-definite (Wensing, Kim and Slotine 2017): m >= 0, and
// the principal moments of I about the centre of mass obey the triangle
// inequalities. The log-Cholesky parameters theta = (alpha, d1, d2, d3,
// s12, s23, s13, t1, t2, t3) (Rucker and Wensing 2022) reach every
// positive-definite J and nothing else:
//   J = U U^T,  U = e^alpha [[e^d1, s12, s13, t1], [0, e^d2, s23, t2],
//                             [0, 0, e^d3, t3], [0, 0, 0, 1]],
// so a fit in theta stays physical with no constraint to enforce.
#pragma once

#include <array>
#include <cmath>

#include "models/serial_robot.h"

namespace driveid {

/// pi from the log-Cholesky parameters (T: double or a Ceres Jet).
template <class T>
void InertialFromLogCholesky(const T* theta, T* pi) {
  using std::exp;
  const T a1 = exp(theta[1]), a2 = exp(theta[2]), a3 = exp(theta[3]);
  const T &s12 = theta[4], &s23 = theta[5], &s13 = theta[6], &t1 = theta[7], &t2 = theta[8], &t3 = theta[9];
  const T scale = exp(T(2.0) * theta[0]);
  // Rows of U / e^alpha; J_ij = e^(2 alpha) v_i . v_j.
  const std::array<std::array<T, 4>, 4> v = {{{a1, s12, s13, t1},
                                              {T(0.0), a2, s23, t2},
                                              {T(0.0), T(0.0), a3, t3},
                                              {T(0.0), T(0.0), T(0.0), T(1.0)}}};
  const auto j = [&](int r, int c) {
    T sum = T(0.0);
    for (int k = 0; k < 4; ++k) sum += v[r][k] * v[c][k];
    return scale * sum;
  };
  const T sxx = j(0, 0), syy = j(1, 1), szz = j(2, 2);
  pi[0] = j(3, 3);
  pi[1] = j(0, 3);
  pi[2] = j(1, 3);
  pi[3] = j(2, 3);
  // I = tr(Sigma) 1 - Sigma.
  pi[4] = syy + szz;
  pi[5] = -j(0, 1);
  pi[6] = -j(0, 2);
  pi[7] = sxx + szz;
  pi[8] = -j(1, 2);
  pi[9] = sxx + syy;
}

/// The log-Cholesky parameters of pi, its pseudo-inertia made positive
/// definite first by adding `floor` (relative to its largest entry) to the
/// diagonal: the start of a consistent fit from a URDF's (perhaps massless
/// or flat) inertials.
std::array<double, 10> LogCholeskyFromInertial(const InertialParameters& pi, double floor = 1e-6);

/// The smallest eigenvalue of the pseudo-inertia, relative to its largest
/// (>= 0 for a physical body, up to rounding).
double PseudoInertiaMargin(const InertialParameters& pi);

}  // namespace driveid
