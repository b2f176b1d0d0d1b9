// Planar robot kinematics (docs/models.md#planar-robot) against finite differences and identities.
#include "models/planar_robot.h"

#include <cmath>

#include <catch2/catch.hpp>

using namespace driveid;

namespace {
const PlanarRobotParameters kRobot;
const Vector2 kCentre = {0.5, 0.5 / std::sqrt(3.0)};
}  // namespace

TEST_CASE("inverse and forward kinematics agree; links have length l; elbow side") {
  const auto bases = CalcBaseJoints(1.0);
  for (double dx : {-0.1, 0.0, 0.12}) {
    for (double dy : {-0.08, 0.0, 0.1}) {
      const Vector2 c = {kCentre[0] + dx, kCentre[1] + dy};
      const Vector3 theta = CalcInverseKinematics(kRobot, c);
      for (std::size_t i = 0; i < 3; ++i) {
        const double bx = bases[i][0] + 0.488 * std::cos(theta[i]), by = bases[i][1] + 0.488 * std::sin(theta[i]);
        CHECK(std::hypot(c[0] - bx, c[1] - by) == Approx(0.488));
        // elbow +1: B_i counter-clockwise of A_i -> C (positive cross product).
        const double cross = (c[0] - bases[i][0]) * (by - bases[i][1]) - (c[1] - bases[i][1]) * (bx - bases[i][0]);
        CHECK(cross > 0.0);
      }
      const Vector2 back = CalcForwardKinematics(kRobot, theta, kCentre);
      CHECK(back[0] == Approx(c[0]).margin(1e-12));
      CHECK(back[1] == Approx(c[1]).margin(1e-12));
    }
  }
  CHECK_THROWS_AS(CalcInverseKinematics(kRobot, {2.5, 0.0}), std::domain_error);
}

TEST_CASE("closure: zero for assembled angles, the leg mismatch for a moved joint, the elbow side") {
  const Vector2 c = {kCentre[0] + 0.07, kCentre[1] - 0.02};
  const Vector3 theta = CalcInverseKinematics(kRobot, c);
  const ClosureCheck closed = CalcClosure(kRobot, theta, CalcForwardKinematics(kRobot, theta, kCentre));
  CHECK(closed.length_error < 1e-12);
  CHECK(closed.wrong_elbow == 0);
  // Elbow B_1 rotated by 0.1 rad about A_1 while C stays: |C - B_1| changes
  // by the chord geometry, computed here independently.
  Vector3 moved = theta;
  moved[0] += 0.1;
  const double bx = 0.488 * std::cos(moved[0]), by = 0.488 * std::sin(moved[0]);
  const double expected = std::abs(std::hypot(c[0] - bx, c[1] - by) - 0.488) / 0.488;
  CHECK(CalcClosure(kRobot, moved, c).length_error == Approx(expected));
  // The mirror-image elbow of leg 3 closes the robot too, on the other side.
  PlanarRobotParameters mirrored = kRobot;
  mirrored.elbow[2] = -1;
  const Vector3 other = CalcInverseKinematics(mirrored, c);
  const ClosureCheck flipped = CalcClosure(kRobot, other, c);
  CHECK(flipped.length_error < 1e-12);
  CHECK(flipped.wrong_elbow == 3);
}

TEST_CASE("theta' = G' x' and dG/dt against finite differences") {
  const Vector2 c = {kCentre[0] + 0.05, kCentre[1] - 0.03};
  const Vector2 v = {0.7, -1.3};
  const double h = 1e-6;
  const Vector3 t0 = CalcInverseKinematics(kRobot, c);
  const Vector3 t1 = CalcInverseKinematics(kRobot, {c[0] + h * v[0], c[1] + h * v[1]});
  const Vector3 tm = CalcInverseKinematics(kRobot, {c[0] - h * v[0], c[1] - h * v[1]});
  const Matrix23 g = CalcTransposedInverseJacobian(kRobot, c, t0);
  for (std::size_t i = 0; i < 3; ++i) {
    CHECK(g(0, i) * v[0] + g(1, i) * v[1] == Approx((t1[i] - tm[i]) / (2 * h)).epsilon(1e-6));
  }
  const Matrix23 g1 = CalcTransposedInverseJacobian(kRobot, {c[0] + h * v[0], c[1] + h * v[1]}, t1);
  const Matrix23 gm = CalcTransposedInverseJacobian(kRobot, {c[0] - h * v[0], c[1] - h * v[1]}, tm);
  const Matrix23 rate = CalcTransposedInverseJacobianRate(kRobot, c, t0, v);
  for (int row = 0; row < 2; ++row) {
    for (int col = 0; col < 3; ++col) {
      CHECK(rate(row, col) == Approx((g1(row, col) - gm(row, col)) / (2 * h)).epsilon(1e-5).margin(1e-8));
    }
  }
}

TEST_CASE("null space, pseudo-inverse and the Cartesian mass matrix") {
  const Vector3 theta = CalcInverseKinematics(kRobot, kCentre);
  const Matrix23 g = CalcTransposedInverseJacobian(kRobot, kCentre, theta);
  const Vector3 n = CalcNullSpace(g);
  CHECK(g(0, 0) * n[0] + g(0, 1) * n[1] + g(0, 2) * n[2] == Approx(0.0).margin(1e-12));
  CHECK(g(1, 0) * n[0] + g(1, 1) * n[1] + g(1, 2) * n[2] == Approx(0.0).margin(1e-12));
  // G G+ f = f.
  const Vector2 f = {3.0, -2.0};
  const Vector3 tau = ApplyPseudoInverse(g, f);
  CHECK(g(0, 0) * tau[0] + g(0, 1) * tau[1] + g(0, 2) * tau[2] == Approx(f[0]));
  CHECK(g(1, 0) * tau[0] + g(1, 1) * tau[1] + g(1, 2) * tau[2] == Approx(f[1]));
  // At the symmetric centre G G' is isotropic, so M is a multiple of 1.
  const Matrix2 m = CalcCartesianMass(kRobot, g);
  CHECK(m(0, 1) == Approx(0.0).margin(1e-9));
  CHECK(m(0, 0) == Approx(m(1, 1)));
  CHECK(m(0, 0) > kRobot.center_mass);
  // Anywhere, M is symmetric to the last bit (a mass matrix), and so is the
  // viscous part of C (the Theta G dG' part is not symmetric in general).
  const Vector2 off_centre = {0.42, 0.21};
  const Vector3 theta_off = CalcInverseKinematics(kRobot, off_centre);
  const Matrix23 g_off = CalcTransposedInverseJacobian(kRobot, off_centre, theta_off);
  const Matrix2 m_off = CalcCartesianMass(kRobot, g_off);
  CHECK(m_off(0, 1) == m_off(1, 0));
  CHECK(std::abs(m_off(0, 1)) > 1e-3);  // really off-diagonal there
  const Matrix2 c_rest = CalcCartesianDamping(kRobot, g_off, Matrix23::Zero());
  CHECK(c_rest(0, 1) == c_rest(1, 0));
}
