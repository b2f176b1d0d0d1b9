#include "models/cdrive.h"

#include <cmath>

namespace driveid {

// Symbols of models/cdrive.h (docs/models.md#c-drive): the nuts turn the
// collar by their mean angle and move it by their difference, one lead p
// per turn: u = p/(4 pi) (psi_L - psi_R), theta = (psi_L + psi_R)/2.
Matrix2 CalcCDriveJacobian(double lead) {
  const double k = lead / (4.0 * M_PI);
  return (Matrix2() << k, -k, k, k).finished();
}

Matrix2 CalcCDriveJacobianInverse(double lead) {
  const double k = 2.0 * M_PI / lead;
  return (Matrix2() << k, k, -k, k).finished();
}

double CalcCollarTranslation(double lead, double psi_left, double psi_right) {
  return lead / (4.0 * M_PI) * (psi_left - psi_right);
}

double CalcCollarRotation(double psi_left, double psi_right) { return 0.5 * (psi_left + psi_right); }

// The inertia matrix follows from the kinetic energy in motor coordinates,
//   T = 1/2 I_h (psi_L'^2 + psi_R'^2) + 1/2 I_c theta'^2 + 1/2 m u'^2,
// with theta' = (psi_L' + psi_R')/2 and u' = p/(4 pi) (psi_L' - psi_R'):
//   M = I_h 1 + I_c/4 [[1, 1], [1, 1]] + m p^2/(16 pi^2) [[1, -1], [-1, 1]].
// The collar's rotation couples the motors positively, its translation
// negatively; the mass term is small for a fine lead (p^2/(16 pi^2)).
double CalcMassCoupling(double lead) { return lead * lead / (16.0 * M_PI * M_PI); }

double CalcInertiaDiagonal(const CDriveParameters& p) {
  return p.hub_inertia + 0.25 * p.collar_inertia + CalcMassCoupling(p.lead) * p.collar_mass;
}

double CalcInertiaOffDiagonal(const CDriveParameters& p) {
  return 0.25 * p.collar_inertia - CalcMassCoupling(p.lead) * p.collar_mass;
}

Matrix2 CalcCDriveInertiaMatrix(const CDriveParameters& p) {
  const double a = CalcInertiaDiagonal(p), b = CalcInertiaOffDiagonal(p);
  return (Matrix2() << a, b, b, a).finished();
}

// Viscous friction from the Rayleigh dissipation function
//   R = 1/2 beta (psi_L'^2 + psi_R'^2) + 1/4 gamma (psi_L' - psi_R')^2,
// beta at each motor's bearings, gamma of the collar on the screws, which
// only the nuts' relative rate loads; C = d^2 R / d psi'^2. The Coulomb
// torques split the same way (delta per motor, eta on the relative rate).
Matrix2 CalcCDriveDampingMatrix(const CDriveParameters& p) {
  const double diagonal = p.viscous_motor + 0.5 * p.viscous_collar;
  const double off = -0.5 * p.viscous_collar;
  return (Matrix2() << diagonal, off, off, diagonal).finished();
}

Vector2 CalcCDriveCoulombTorque(const CDriveParameters& p, double rate_left, double rate_right) {
  const double collar = p.coulomb_collar * Signum(rate_left - rate_right);
  return {p.coulomb_motor * Signum(rate_left) + collar, p.coulomb_motor * Signum(rate_right) - collar};
}

double CalcCDriveDissipatedPower(const CDriveParameters& p, double rate_left, double rate_right) {
  const Matrix2 c = CalcCDriveDampingMatrix(p);
  const Vector2 coulomb = CalcCDriveCoulombTorque(p, rate_left, rate_right);
  const double left = c(0, 0) * rate_left + c(0, 1) * rate_right + coulomb[0];
  const double right = c(1, 0) * rate_left + c(1, 1) * rate_right + coulomb[1];
  return rate_left * left + rate_right * right;
}

Vector2 CalcCDriveInverseDynamics(const CDriveParameters& p, const Vector2& rate, const Vector2& acceleration) {
  const Matrix2 m = CalcCDriveInertiaMatrix(p);
  const Matrix2 c = CalcCDriveDampingMatrix(p);
  const Vector2 coulomb = CalcCDriveCoulombTorque(p, rate[0], rate[1]);
  return {m(0, 0) * acceleration[0] + m(0, 1) * acceleration[1] + c(0, 0) * rate[0] + c(0, 1) * rate[1] + coulomb[0],
          m(1, 0) * acceleration[0] + m(1, 1) * acceleration[1] + c(1, 0) * rate[0] + c(1, 1) * rate[1] + coulomb[1]};
}

}  // namespace driveid
