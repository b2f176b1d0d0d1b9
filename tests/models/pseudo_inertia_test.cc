// Log-Cholesky parameters (models/pseudo_inertia.h): every parameter vector
// maps to a physical body (mass > 0, principal moments about the centre
// obey the triangle inequalities, computed here from the inertia matrix);
// a physical body maps back to itself.
#include <random>

#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>

#include "models/pseudo_inertia.h"

using namespace driveid;

TEST_CASE("log-Cholesky parameters give physical bodies, and physical bodies round-trip") {
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 200; ++trial) {
    double theta[10];
    for (double& t : theta) t = normal(rng);
    InertialParameters pi{};
    InertialFromLogCholesky(theta, pi.data());
    REQUIRE(pi[0] > 0.0);
    const Eigen::Vector3d c = Eigen::Vector3d(pi[1], pi[2], pi[3]) / pi[0];
    const Eigen::Matrix3d at_centre =
        InertiaMatrix(pi) - pi[0] * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
    const Eigen::Vector3d moments = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(at_centre).eigenvalues();
    const double tolerance = 1e-9 * moments.cwiseAbs().maxCoeff();
    CHECK(moments(0) >= -tolerance);
    CHECK(moments(0) + moments(1) >= moments(2) - tolerance);
    CHECK(PseudoInertiaMargin(pi) >= -1e-12);
    const std::array<double, 10> back = LogCholeskyFromInertial(pi, 0.0);
    InertialParameters again{};
    InertialFromLogCholesky(back.data(), again.data());
    for (std::size_t k = 0; k < 10; ++k) CHECK(again[k] == Approx(pi[k]).margin(1e-9 * (1.0 + std::abs(pi[k]))));
  }
}

TEST_CASE("a body with a violated triangle inequality has a negative pseudo-inertia margin") {
  // Principal moments 1, 1, 3 about the centre: 1 + 1 < 3, not a body.
  const InertialParameters bad = InertialFromCentre(2.0, Eigen::Vector3d(0.1, 0.0, 0.0), Eigen::Vector3d(1, 1, 3).asDiagonal());
  CHECK(PseudoInertiaMargin(bad) < 0.0);
  const InertialParameters good = InertialFromCentre(2.0, Eigen::Vector3d(0.1, 0.0, 0.0), Eigen::Vector3d(1, 2, 2.5).asDiagonal());
  CHECK(PseudoInertiaMargin(good) > 0.0);
}
