// report/planar_robot_report.h at a pose off the centre: theta' = G' x'
// against central differences of the inverse kinematics, G n = 0 with n a
// unit vector, M = Theta G G' + m_c 1 symmetric positive definite, C at rest
// n_g^2 d_g G G', and a pose out of reach refused.
#include "report/planar_robot_report.h"

#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>

#include "params/parameter_file.h"

using namespace driveid;

TEST_CASE("planar robot report: G against the kinematics' differences, null space, M and C") {
  const char* source = std::getenv("DRIVEID_SOURCE_DIR");
  const ParameterFile file = ReadParameterFile(std::string(source ? source : ".") + "/data/robot_paper000.yaml");
  const PlanarRobotParameters robot = MakePlanarRobotParameters(*file.Find<PlanarRobotSection>());
  const double a = robot.base_distance;
  const Vector2 pose{0.45 * a, 0.3 * a};
  const PlanarRobotReport r = CalcPlanarRobotReport(robot, pose, Vector2{0.0, 0.0}, "robot.yaml");
  const double h = 1e-7;
  for (int i = 0; i < 2; ++i) {
    Vector2 up = pose, down = pose;
    up(i) += h;
    down(i) -= h;
    const Vector3 rate = (CalcInverseKinematics(robot, up) - CalcInverseKinematics(robot, down)) / (2.0 * h);
    for (int j = 0; j < 3; ++j) CHECK(r.g(i, j) == Approx(rate(j)).epsilon(1e-5));
  }
  CHECK((r.g * r.n).norm() == Approx(0.0).margin(1e-9));
  CHECK(r.n.norm() == Approx(1.0));
  const Matrix2 m = robot.output_inertia * r.g * r.g.transpose() + robot.center_mass * Matrix2::Identity();
  CHECK((r.m - m).norm() == Approx(0.0).margin(1e-9 * m.norm()));
  CHECK(r.m(0, 1) == Approx(r.m(1, 0)));
  CHECK(Eigen::SelfAdjointEigenSolver<Matrix2>(r.m).eigenvalues().minCoeff() > 0.0);
  const Matrix2 c = robot.gear_ratio * robot.gear_ratio * robot.viscous_friction * r.g * r.g.transpose();
  CHECK((r.c - c).norm() == Approx(0.0).margin(1e-9 * c.norm()));
  CHECK_THROWS_AS(CalcPlanarRobotReport(robot, Vector2{10.0 * a, 10.0 * a}, Vector2{0.0, 0.0}, "robot.yaml"),
                  std::domain_error);
  CHECK(FormatPlanarRobotReport(r).find("robot.yaml") != std::string::npos);
  CHECK(PlanarRobotReportJson(r).is_object());
}
