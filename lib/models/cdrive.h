// The two-motor ball-screw C-drive (seed 001, RHHR cylindrical differential;
// docs/models.md#c-drive, corrected equations).
//
// Kinematics (eqs. 3-13), motor angles psi = (psi_L, psi_R) [rad], lead p [m]:
//   u = p/(4 pi) (psi_L - psi_R)   collar translation [m]
//   theta = (psi_L + psi_R) / 2    collar rotation [rad],  v = p theta / (2 pi)
//   w = (u, v) = J psi,  J = p/(4 pi) [[1, -1], [1, 1]],  J'J = p^2/(8 pi^2) 1
//   J^-1 = (2 pi / p) [[1, 1], [-1, 1]]   (the seed prints pi/p, which gives J J^-1 = 1/2)
// Inertia (17): M = [[a, b], [b, a]],  a = I_h + I_c/4 + p^2 m/(16 pi^2),
//   b = I_c/4 - p^2 m/(16 pi^2). Only a and b are identifiable from motor torques.
// Dissipation: C = [[beta + gamma/2, -gamma/2], [-gamma/2, beta + gamma/2]]
//   (symmetric: the Hessian of Delta_v; the seed prints +gamma/2 lower left),
//   phi_c = [delta sgn psi_L' + eta sgn(psi_L' - psi_R'), delta sgn psi_R' + eta sgn(psi_R' - psi_L')],
//   sgn(0) = 0.
// Dynamics (28): M psi'' + C psi' + phi_c = tau.
//
// Friction acts at three contacts: motor L (velocity psi_L', limit delta,
// direction (1, 0)), motor R (psi_R', delta, (0, 1)) and the collar on the
// screws (psi_L' - psi_R', eta, (1, -1)). The generalised friction force is
// sum_i f_i g_i with f_i = limit_i sgn(v_i) while contact i slides.
#pragma once

#include <array>

#include <Eigen/Core>
#include <optional>

#include "models/parameter_table.h"

namespace driveid {

/// C-drive parameters (section `cdrive`).
struct CDriveParameters {
  double lead = 0.06;            ///< p, screw lead [m]
  double hub_inertia = 0.0;      ///< I_h, motor rotor + coupling + screw [kg m^2]
  double collar_inertia = 0.0;   ///< I_c, collar about the screw axis [kg m^2]
  double collar_mass = 0.0;      ///< m, collar [kg]
  double viscous_motor = 0.0;    ///< beta, rotor/bearing viscous [N m s/rad]
  double viscous_collar = 0.0;   ///< gamma, collar/screw viscous [N m s/rad]
  double coulomb_motor = 0.0;    ///< delta, rotor/bearing Coulomb [N m]
  double coulomb_collar = 0.0;   ///< eta, collar/screw Coulomb [N m]
};

/// The parameter file's `cdrive` section as written (the controller
/// settings, `cdrive.control`, are read beside it).
struct CDriveSection {
  static constexpr const char* kSectionName = "cdrive";
  std::optional<double> lead, hub_inertia, collar_inertia, collar_mass, viscous_motor, viscous_collar, coulomb_motor,
      coulomb_collar;
  std::optional<double> torque_constant;  ///< k_t [N m/A], for logs of currents
};

/// The C-drive's parameters: the "friction" fit estimates beta..eta, the
/// "inertia" fit I_h, I_c, m (default I_h, I_c); `typical` scales a fit
/// started from no value.
inline const ParameterTable<CDriveSection, CDriveParameters>& CDriveParameterTable() {
  using S = CDriveSection;
  using P = CDriveParameters;
  static const ParameterTable<S, P> table = {
      {Spec("p", "p", "m", "screw lead").Above(0.0).Required(), &S::lead, &P::lead},
      {Spec("I_h", "I_h", "kg m^2", "motor rotor + coupling + screw inertia").Fit("inertia").FreeByDefault()
           .Typical(1e-4),
       &S::hub_inertia, &P::hub_inertia},
      {Spec("I_c", "I_c", "kg m^2", "collar inertia about the screw axis").Fit("inertia").FreeByDefault().Typical(1e-4),
       &S::collar_inertia, &P::collar_inertia},
      {Spec("m", "m", "kg", "collar mass").Fit("inertia").Typical(1.0), &S::collar_mass, &P::collar_mass},
      {Spec("beta", "beta", "N m s/rad", "viscous, rotor and bearings").Fit("friction").FreeByDefault().Typical(1e-3),
       &S::viscous_motor, &P::viscous_motor},
      {Spec("gamma", "gamma", "N m s/rad", "viscous, collar on the screws").Fit("friction").FreeByDefault()
           .Typical(1e-3),
       &S::viscous_collar, &P::viscous_collar},
      {Spec("delta", "delta", "N m", "Coulomb, rotor and bearings").Fit("friction").FreeByDefault().Typical(0.1),
       &S::coulomb_motor, &P::coulomb_motor},
      {Spec("eta", "eta", "N m", "Coulomb, collar on the screws").Fit("friction").FreeByDefault().Typical(0.1),
       &S::coulomb_collar, &P::coulomb_collar},
      {Spec("k_t", "k_t", "N m/A", "motor torque constant").Above(0.0), &S::torque_constant,
       nullptr},
  };
  return table;
}

using Vector2 = Eigen::Vector2d;
using Matrix2 = Eigen::Matrix2d;

/// Actuator Jacobian J (eq. 10), w = J psi.
Matrix2 CalcCDriveJacobian(double lead);
/// Its inverse (2 pi / p) [[1, 1], [-1, 1]] (corrected eq. 12).
Matrix2 CalcCDriveJacobianInverse(double lead);

/// Collar translation u [m] and rotation theta [rad] from motor angles.
double CalcCollarTranslation(double lead, double psi_left, double psi_right);
double CalcCollarRotation(double psi_left, double psi_right);

/// p^2 / (16 pi^2) [m^2/rad^2]: how the collar mass enters M.
double CalcMassCoupling(double lead);
/// Diagonal a and off-diagonal b of M (eq. 17) [kg m^2].
double CalcInertiaDiagonal(const CDriveParameters& params);
double CalcInertiaOffDiagonal(const CDriveParameters& params);
Matrix2 CalcCDriveInertiaMatrix(const CDriveParameters& params);
/// Dissipation matrix C (eq. 27a, symmetric) [N m s/rad].
Matrix2 CalcCDriveDampingMatrix(const CDriveParameters& params);

/// sgn with sgn(0) = 0.
inline double Signum(double value) { return static_cast<double>((value > 0.0) - (value < 0.0)); }

/// Coulomb vector phi_c (eq. 27b) [N m].
Vector2 CalcCDriveCoulombTorque(const CDriveParameters& params, double rate_left, double rate_right);

/// Dissipated power psi'^T (C psi' + phi_c) [W]; >= 0 for nonnegative coefficients.
double CalcCDriveDissipatedPower(const CDriveParameters& params, double rate_left, double rate_right);

/// Motor torques from (28) for given rates and accelerations (inverse dynamics).
Vector2 CalcCDriveInverseDynamics(const CDriveParameters& params, const Vector2& rate, const Vector2& acceleration);

}  // namespace driveid
