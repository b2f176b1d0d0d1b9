#include "models/joint.h"

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

namespace driveid {

SampledJointResponse::SampledJointResponse(const JointParameters& p, double gear_ratio, double rate)
    : gear_ratio_(gear_ratio), period_(1.0 / rate) {
  const double jm = p.motor_inertia, jl = p.link_inertia, k = p.stiffness, d = p.damping;
  a_ = {{{0.0, 1.0, 0.0, 0.0},
         {-k / jm, -(p.motor_viscous + d) / jm, k / jm, d / jm},
         {0.0, 0.0, 0.0, 1.0},
         {k / jl, d / jl, -k / jl, -(p.link_viscous + d) / jl}}};
  b_ = {0.0, gear_ratio / jm, 0.0, 0.0};  // input: the logged torque, tau_m = n tau
  Eigen::Matrix<double, 5, 5> augmented = Eigen::Matrix<double, 5, 5>::Zero();
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) augmented(i, j) = a_[i][j] * period_;
    augmented(i, 4) = b_[i] * period_;
  }
  const Eigen::Matrix<double, 5, 5> e = augmented.exp();
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) phi_[i][j] = e(i, j);
    gamma_[i] = e(i, 4);
  }
}

std::complex<double> SampledJointResponse::Evaluate(double omega, const std::array<double, 4>& c, double d) const {
  const std::complex<double> z = std::exp(std::complex<double>(0.0, omega * period_));
  Eigen::Matrix4cd m;
  Eigen::Vector4cd g;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) m(i, j) = (i == j ? z : 0.0) - phi_[i][j];
    g(i) = gamma_[i];
  }
  const Eigen::Vector4cd x = m.partialPivLu().solve(g);
  std::complex<double> y = d;
  for (int i = 0; i < 4; ++i) y += c[i] * x(i);
  return y;
}

std::complex<double> SampledJointResponse::Motor(double omega, ResponseQuantity quantity) const {
  const double n = gear_ratio_;  // q_motor = n theta_m
  switch (quantity) {
    case ResponseQuantity::kPosition: return Evaluate(omega, {n, 0.0, 0.0, 0.0}, 0.0);
    case ResponseQuantity::kRate: return Evaluate(omega, {0.0, n, 0.0, 0.0}, 0.0);
    case ResponseQuantity::kAcceleration:
      return Evaluate(omega, {n * a_[1][0], n * a_[1][1], n * a_[1][2], n * a_[1][3]}, n * b_[1]);
  }
  return 0.0;
}

std::complex<double> SampledJointResponse::Link(double omega, ResponseQuantity quantity) const {
  switch (quantity) {
    case ResponseQuantity::kPosition: return Evaluate(omega, {0.0, 0.0, 1.0, 0.0}, 0.0);
    case ResponseQuantity::kRate: return Evaluate(omega, {0.0, 0.0, 0.0, 1.0}, 0.0);
    case ResponseQuantity::kAcceleration: return Evaluate(omega, {a_[3][0], a_[3][1], a_[3][2], a_[3][3]}, b_[3]);
  }
  return 0.0;
}

std::vector<std::string> TwoMassDefaultFree() {
  std::vector<std::string> keys;
  for (const auto member : {&JointParameters::motor_inertia, &JointParameters::link_inertia, &JointParameters::stiffness,
                            &JointParameters::damping, &JointParameters::motor_viscous}) {
    keys.push_back(KeyOf(JointParameterTable(), member));
  }
  return keys;
}

}  // namespace driveid
