#include "models/pseudo_inertia.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

namespace driveid {
namespace {

Eigen::Matrix4d PseudoInertia(const InertialParameters& pi) {
  const Eigen::Matrix3d inertia = InertiaMatrix(pi);
  const Eigen::Matrix3d sigma = 0.5 * inertia.trace() * Eigen::Matrix3d::Identity() - inertia;
  Eigen::Matrix4d j;
  j.topLeftCorner<3, 3>() = sigma;
  j.topRightCorner<3, 1>() = Eigen::Vector3d(pi[1], pi[2], pi[3]);
  j.bottomLeftCorner<1, 3>() = Eigen::Vector3d(pi[1], pi[2], pi[3]).transpose();
  j(3, 3) = pi[0];
  return j;
}

}  // namespace

std::array<double, 10> LogCholeskyFromInertial(const InertialParameters& pi, double floor) {
  Eigen::Matrix4d j = PseudoInertia(pi);
  const double largest = std::max(j.cwiseAbs().maxCoeff(), 1e-12);
  // Made positive definite: the smallest eigenvalue raised to floor x largest.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(j);
  const double lift = std::max(0.0, floor * largest - eigen.eigenvalues()(0));
  j += lift * Eigen::Matrix4d::Identity();
  // J = U U^T with U upper triangular: with P the exchange matrix,
  // P J P = L L^T (Cholesky) and U = P L P.
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  for (int i = 0; i < 4; ++i) p(i, 3 - i) = 1.0;
  const Eigen::Matrix4d l = Eigen::LLT<Eigen::Matrix4d>(p * j * p).matrixL();
  const Eigen::Matrix4d u = p * l * p;
  const double e = u(3, 3);  // e^alpha
  return {std::log(e),     std::log(u(0, 0) / e), std::log(u(1, 1) / e), std::log(u(2, 2) / e), u(0, 1) / e,
          u(1, 2) / e,     u(0, 2) / e,           u(0, 3) / e,           u(1, 3) / e,           u(2, 3) / e};
}

double PseudoInertiaMargin(const InertialParameters& pi) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(PseudoInertia(pi));
  const double largest = eigen.eigenvalues().cwiseAbs().maxCoeff();
  return largest > 0.0 ? eigen.eigenvalues()(0) / largest : 0.0;
}

}  // namespace driveid
