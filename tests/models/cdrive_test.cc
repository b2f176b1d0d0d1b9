// C-drive model checks (docs/models.md#c-drive): kinematic identities, inertia matrix
// properties, dissipation, and the Table II motion cases.
#include "models/cdrive.h"

#include <cmath>

#include <catch2/catch.hpp>

#include "support/paper001.h"

using namespace driveid;

namespace {
using testing_support::TableOneCDrive;
}  // namespace

TEST_CASE("J J^-1 = 1 and J'J = p^2/(8 pi^2) 1 (isotropy)") {
  for (double lead : {0.06, 0.01, 0.2}) {
    const Matrix2 j = CalcCDriveJacobian(lead);
    const Matrix2 identity = j * CalcCDriveJacobianInverse(lead);
    CHECK(identity(0, 0) == Approx(1.0));
    CHECK(identity(0, 1) == Approx(0.0).margin(1e-12));
    CHECK(identity(1, 0) == Approx(0.0).margin(1e-12));
    CHECK(identity(1, 1) == Approx(1.0));
    const Matrix2 jt = j.transpose();
    const Matrix2 jtj = jt * j;
    CHECK(jtj(0, 0) == Approx(lead * lead / (8 * M_PI * M_PI)));
    CHECK(jtj(1, 1) == Approx(lead * lead / (8 * M_PI * M_PI)));
    CHECK(jtj(0, 1) == Approx(0.0).margin(1e-15));
  }
}

TEST_CASE("kinematics: J psi gives (u, p theta / 2 pi)") {
  const double lead = 0.06, left = 3.0, right = -1.0;
  const Matrix2 j = CalcCDriveJacobian(lead);
  CHECK(j(0, 0) * left + j(0, 1) * right == Approx(CalcCollarTranslation(lead, left, right)));
  CHECK(j(1, 0) * left + j(1, 1) * right == Approx(lead / (2 * M_PI) * CalcCollarRotation(left, right)));
}

TEST_CASE("M is symmetric positive definite, and proportional to 1 under eq. (18)") {
  const auto p = TableOneCDrive();
  const Matrix2 m = CalcCDriveInertiaMatrix(p);
  CHECK(m(0, 1) == m(1, 0));
  CHECK(m(0, 0) > 0.0);
  CHECK(m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0) > 0.0);
  // M = J' diag(m, (2 pi/p)^2 I_c) J + I_h 1 (eq. 16), computed independently.
  const Matrix2 j = CalcCDriveJacobian(p.lead);
  const Matrix2 jt = j.transpose();
  const double k = 2 * M_PI / p.lead;
  const Matrix2 d = Eigen::Vector2d(p.collar_mass, k * k * p.collar_inertia).asDiagonal();
  const Matrix2 mc = jt * d * j;
  CHECK(m(0, 0) == Approx(mc(0, 0) + p.hub_inertia));
  CHECK(m(0, 1) == Approx(mc(0, 1)));
  auto isotropic = p;
  isotropic.collar_inertia = std::pow(p.lead / (2 * M_PI), 2) * p.collar_mass;
  const Matrix2 mi = CalcCDriveInertiaMatrix(isotropic);
  CHECK(mi(0, 1) == Approx(0.0).margin(1e-18));
  CHECK(mi(0, 0) == Approx(isotropic.hub_inertia + isotropic.collar_inertia / 2));
}

TEST_CASE("C is symmetric and the Hessian of Delta_v; dissipated power is never negative") {
  const auto p = TableOneCDrive();
  const Matrix2 c = CalcCDriveDampingMatrix(p);
  CHECK(c(0, 1) == c(1, 0));
  // Delta_v = beta/2 (L^2 + R^2) + gamma/2 [(L - theta')^2 + (R - theta')^2], theta' = (L + R)/2.
  auto delta_v = [&](double l, double r) {
    const double th = 0.5 * (l + r);
    return 0.5 * p.viscous_motor * (l * l + r * r) + 0.5 * p.viscous_collar * ((l - th) * (l - th) + (r - th) * (r - th));
  };
  const double h = 1e-3;
  CHECK((delta_v(h, h) - delta_v(h, -h) - delta_v(-h, h) + delta_v(-h, -h)) / (4 * h * h) == Approx(c(0, 1)));
  CHECK((delta_v(h, 0) - 2 * delta_v(0, 0) + delta_v(-h, 0)) / (h * h) == Approx(c(0, 0)));
  for (double l = -3; l <= 3; l += 0.37) {
    for (double r = -3; r <= 3; r += 0.41) CHECK(CalcCDriveDissipatedPower(p, l, r) >= 0.0);
  }
  CHECK(CalcCDriveDissipatedPower(p, 0.0, 0.0) == 0.0);
}

TEST_CASE("Table II: pure rotation carries no collar friction, pure translation does") {
  const auto p = TableOneCDrive();
  // Rotation: psi_L' = psi_R' -> collar at rest on the screws: no gamma, no eta.
  const Vector2 rotation = CalcCDriveInverseDynamics(p, {2.0, 2.0}, {0.0, 0.0});
  CHECK(rotation[0] == Approx(p.viscous_motor * 2.0 + p.coulomb_motor));
  CHECK(rotation[1] == Approx(rotation[0]));
  CHECK(CalcCollarTranslation(p.lead, 2.0, 2.0) == 0.0);
  // Translation: psi_L' = -psi_R': antisymmetric torques with gamma and eta.
  const Vector2 translation = CalcCDriveInverseDynamics(p, {2.0, -2.0}, {0.0, 0.0});
  CHECK(translation[0] == Approx((p.viscous_motor + p.viscous_collar) * 2.0 + p.coulomb_motor + p.coulomb_collar));
  CHECK(translation[1] == Approx(-translation[0]));
  CHECK(CalcCollarRotation(2.0, -2.0) == 0.0);
  // sgn(0) = 0: at rest there is no Coulomb torque.
  const Vector2 rest = CalcCDriveCoulombTorque(p, 0.0, 0.0);
  CHECK(rest[0] == 0.0);
  CHECK(rest[1] == 0.0);
}
