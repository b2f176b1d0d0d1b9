// Base parameters (fit/core/base_parameters.h): the regrouped model reproduces
// the full one on new motions, their count is the regressor's rank (by
// SVD), and a planar two-link arm regroups as Khalil's rules say:
//   ZZ1R = Izz_1 + armature_1 + l1^2 m_2,  MX1R = mx_1 + l1 m_2.
#include <algorithm>
#include <random>

#include <Eigen/SVD>
#include <catch2/catch.hpp>

#include "fit/core/base_parameters.h"
#include "models/serial_dynamics.h"

using namespace driveid;
using Eigen::Vector3d;

namespace {

Eigen::MatrixXd RandomRows(const SerialRobot& robot, int samples, unsigned seed) {
  const auto n = static_cast<Eigen::Index>(robot.size());
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd w(n * samples, static_cast<Eigen::Index>(kSerialColumnsPerJoint) * n);
  for (int s = 0; s < samples; ++s) {
    Eigen::VectorXd q(n), qd(n), qdd(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      q(i) = 3.0 * normal(rng);
      qd(i) = normal(rng);
      qdd(i) = normal(rng);
    }
    CalcSerialRegressor(robot, q, qd, qdd, w.middleRows(s * n, n));
  }
  return w;
}

SerialRobot PlanarTwoLink(double l1) {
  SerialRobot robot;
  robot.gravity = Vector3d(0.0, -9.81, 0.0);
  SerialJoint a;
  a.name = "a";
  a.body = "one";
  SerialJoint b = a;
  b.name = "b";
  b.body = "two";
  b.parent = 0;
  b.origin.translation = Vector3d(l1, 0.0, 0.0);
  robot.joints = {a, b};
  robot.bodies = {InertialFromCentre(2.0, Vector3d(0.3, 0.05, 0.0), Eigen::Matrix3d::Identity() * 0.04),
                  InertialFromCentre(1.3, Vector3d(0.25, -0.02, 0.0), Eigen::Matrix3d::Identity() * 0.02)};
  return robot;
}

std::size_t Column(const std::vector<std::string>& names, const std::string& name) {
  return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
}

}  // namespace

TEST_CASE("base parameters of a planar two-link arm follow Khalil's regrouping") {
  const double l1 = 0.7;
  const SerialRobot robot = PlanarTwoLink(l1);
  const std::vector<std::string> names = SerialParameterNames(robot);
  const BaseParameters base = FindBaseParameters(RandomRows(robot, 60, 1), names);
  // Inertial: ZZ1R, MX1R, MY1R, ZZ2, MX2, MY2; drives: armature b, viscous,
  // Coulomb and offset of both.
  CHECK(base.base.size() == 13);
  const auto lead = std::find(base.base.begin(), base.base.end(), Column(names, "Izz_one"));
  REQUIRE(lead != base.base.end());
  const auto k = static_cast<Eigen::Index>(lead - base.base.begin());
  CHECK(base.regroup(k, static_cast<Eigen::Index>(Column(names, "armature_a"))) == 1.0);
  CHECK(base.regroup(k, static_cast<Eigen::Index>(Column(names, "m_two"))) == Approx(l1 * l1).epsilon(1e-9));
  const auto mx = std::find(base.base.begin(), base.base.end(), Column(names, "mx_one"));
  REQUIRE(mx != base.base.end());
  CHECK(base.regroup(mx - base.base.begin(), static_cast<Eigen::Index>(Column(names, "m_two"))) ==
        Approx(l1).epsilon(1e-9));
  CHECK(base.names[static_cast<std::size_t>(k)] == "Izz_one + armature_a + 0.49 m_two");
}

TEST_CASE("base parameters reproduce the full model on new motions; their count is the rank") {
  // A 3-joint arm with tilted axes and offsets.
  SerialRobot robot;
  const Vector3d axes[3] = {Vector3d::UnitZ(), Vector3d::UnitY(), Vector3d(0.0, 0.6, 0.8)};
  for (int i = 0; i < 3; ++i) {
    SerialJoint j;
    j.name = "j" + std::to_string(i);
    j.body = "b" + std::to_string(i);
    j.parent = i - 1;
    j.axis = axes[i];
    j.origin.translation = Vector3d(0.1 * i, 0.05, 0.3);
    j.origin.rotation = RotationFromRpy(0.2 * i, -0.1, 0.3);
    robot.joints.push_back(j);
    robot.bodies.push_back(InertialFromCentre(1.0 + i, Vector3d(0.1, -0.05 * i, 0.2), Eigen::Matrix3d::Identity() * 0.1));
  }
  const std::vector<std::string> names = SerialParameterNames(robot);
  const Eigen::MatrixXd fit_rows = RandomRows(robot, 80, 2);
  const BaseParameters base = FindBaseParameters(fit_rows, names);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(fit_rows);
  const Eigen::VectorXd s = svd.singularValues();
  Eigen::Index rank = 0;
  for (Eigen::Index i = 0; i < s.size(); ++i) rank += s(i) > 1e-9 * s(0);
  CHECK(static_cast<Eigen::Index>(base.base.size()) == rank);
  std::mt19937 rng(4);
  std::normal_distribution<double> normal;
  Eigen::VectorXd theta(static_cast<Eigen::Index>(names.size()));
  for (Eigen::Index i = 0; i < theta.size(); ++i) theta(i) = normal(rng);
  const Eigen::MatrixXd fresh = RandomRows(robot, 20, 3);
  Eigen::MatrixXd wb(fresh.rows(), static_cast<Eigen::Index>(base.base.size()));
  for (std::size_t k = 0; k < base.base.size(); ++k) wb.col(static_cast<Eigen::Index>(k)) = fresh.col(static_cast<Eigen::Index>(base.base[k]));
  const Eigen::VectorXd full = fresh * theta, regrouped = wb * (base.regroup * theta);
  CHECK((full - regrouped).norm() <= 1e-9 * full.norm());
}

// The tolerances that decide a dependent and a never-moved column, at the
// columns' own scale: a column whose part outside the earlier columns' span
// is 1e-5 of its norm is a direction of its own, one at 1e-7 is their
// combination (FindBaseParameters' tolerance 1e-6 lies between); a column
// 1e-10 of the largest moves, one 1e-14 never does (1e-12 between).
TEST_CASE("a column at the dependency tolerance: kept above it, regrouped below it, zero below the zero tolerance") {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  const Eigen::Index rows = 40;
  Eigen::MatrixXd a(rows, 2);
  for (Eigen::Index i = 0; i < rows; ++i) a.row(i) << normal(rng), normal(rng);
  // A unit direction orthogonal to a's columns.
  Eigen::VectorXd e(rows);
  for (Eigen::Index i = 0; i < rows; ++i) e(i) = normal(rng);
  const Eigen::MatrixXd q = a.householderQr().householderQ() * Eigen::MatrixXd::Identity(rows, 2);
  e -= q * (q.transpose() * e);
  e.normalize();
  const Eigen::VectorXd combination = 0.6 * a.col(0) - 0.8 * a.col(1);
  const auto with_outside = [&](double fraction) {
    Eigen::MatrixXd w(rows, 3);
    w << a, combination + fraction * combination.norm() * e;
    return w;
  };
  const std::vector<std::string> names = {"a", "b", "c"};
  SECTION("1e-5 outside the span: a base parameter of its own") {
    const BaseParameters base = FindBaseParameters(with_outside(1e-5), names);
    CHECK(base.base == std::vector<std::size_t>{0, 1, 2});
  }
  SECTION("1e-7 outside the span: regrouped into the others") {
    const BaseParameters base = FindBaseParameters(with_outside(1e-7), names);
    CHECK(base.base == std::vector<std::size_t>{0, 1});
    REQUIRE(base.regroup.rows() == 2);
    CHECK(base.regroup(0, 2) == Approx(0.6).margin(1e-6));
    CHECK(base.regroup(1, 2) == Approx(-0.8).margin(1e-6));
  }
  SECTION("a column 1e-10 of the largest moves; 1e-14 never does") {
    Eigen::MatrixXd w(rows, 3);
    w << a, 1e-10 * a.col(0).norm() * e;
    CHECK(FindBaseParameters(w, names).never_moved.empty());
    w.col(2) = 1e-14 * a.col(0).norm() * e;
    CHECK(FindBaseParameters(w, names).never_moved == std::vector<std::size_t>{2});
  }
}
