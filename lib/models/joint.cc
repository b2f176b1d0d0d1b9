#include "models/joint.h"

#include <stdexcept>

#include "models/joint_term.h"

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

namespace driveid {

namespace {

using Complex = std::complex<double>;
using Matrix2c = std::array<std::array<Complex, 2>, 2>;

// The two-mass form of Z(s) = M s^2 + D s + K: every linear term either
// acts on one mass against ground (a diagonal partial) or couples the two
// (a partial c [1 -1; -1 1]), so that Z = diag(G_m, G_l) + C [1 -1; -1 1]
// with A_m = G_m + C, A_l = G_l + C and the coupling K = C.
struct TwoMass {
  Complex motor, link, coupling;  // G_m, G_l, C
};

// A parameter's part of G_m, G_l and C at the value `value`.
TwoMass Contribution(const JointLinearDynamics& partial, double value, Complex s) {
  TwoMass out;
  const auto add = [&](const std::array<std::array<double, 2>, 2>& x, int order) {
    const double coupling = -x[0][1];
    if (x[1][0] != x[0][1]) throw std::logic_error("joint terms: a linear term's partial is not symmetric");
    const std::array<double, 3> coefficients = {x[0][0] - coupling, x[1][1] - coupling, coupling};
    std::array<Complex*, 3> targets = {&out.motor, &out.link, &out.coupling};
    for (std::size_t i = 0; i < 3; ++i) {
      if (coefficients[i] == 0.0) continue;
      Complex term = value * coefficients[i];
      for (int k = 0; k < order; ++k) term *= s;
      *targets[i] += term;
    }
  };
  add(partial.mass, 2);
  add(partial.damping, 1);
  add(partial.stiffness, 0);
  return out;
}

TwoMass Polynomials(const JointParameters& p, Complex s) {
  TwoMass sum;
  for (const std::size_t j : JointLinearParameters()) {
    const TwoMass part = Contribution(JointLinearPartial(j), ModelValue(JointParameterTable()[j], p), s);
    sum.motor += part.motor;
    sum.link += part.link;
    sum.coupling += part.coupling;
  }
  return sum;
}

// The registered inertias act each on its own mass; the state space below
// divides by them.
void RequireDiagonalMass(const JointLinearDynamics& m) {
  if (m.mass[0][1] != 0.0 || m.mass[1][0] != 0.0) {
    throw std::logic_error("joint terms: a term couples the masses' accelerations; the state space needs M diagonal");
  }
}

}  // namespace

JointResponse CalcJointResponse(const JointParameters& p, double gear_ratio, double omega, ResponseQuantity quantity) {
  const Complex s(0.0, omega);
  const TwoMass g = Polynomials(p, s);
  const Complex spring = g.coupling;
  const Complex a_m = g.motor + spring, a_l = g.link + spring;
  const Complex delta = a_m * a_l - spring * spring;
  const Complex derivative = std::pow(s, static_cast<int>(quantity));
  JointResponse out;
  out.motor = gear_ratio * gear_ratio * a_l / delta * derivative;
  out.link = gear_ratio * spring / delta * derivative;
  // d ln(A_l / Delta) = dA_l / A_l - dDelta / Delta, likewise for K.
  const std::vector<std::size_t>& linear = JointLinearParameters();
  for (std::size_t i = 0; i < linear.size(); ++i) {
    const TwoMass d = Contribution(JointLinearPartial(linear[i]), 1.0, s);
    const Complex da_m = d.motor + d.coupling, da_l = d.link + d.coupling, dk = d.coupling;
    const Complex d_delta = da_m * a_l + a_m * da_l - 2.0 * spring * dk;
    out.motor_log_gradient[i] = da_l / a_l - d_delta / delta;
    out.link_log_gradient[i] = dk / spring - d_delta / delta;
  }
  return out;
}

SampledJointResponse::SampledJointResponse(const JointParameters& p, double gear_ratio, double rate)
    : gear_ratio_(gear_ratio), period_(1.0 / rate) {
  // x = (theta_m, theta_m', theta_l, theta_l'): x'' = -M^-1 (D x' + K x) + M^-1 (n tau, 0).
  const JointLinearDynamics m = CalcJointLinearDynamics(p);
  RequireDiagonalMass(m);
  for (int mass = 0; mass < 2; ++mass) {
    const double inertia = m.mass[mass][mass];
    auto& row = a_[static_cast<std::size_t>(2 * mass + 1)];
    a_[static_cast<std::size_t>(2 * mass)][static_cast<std::size_t>(2 * mass + 1)] = 1.0;
    for (int other = 0; other < 2; ++other) {
      row[static_cast<std::size_t>(2 * other)] = -m.stiffness[mass][other] / inertia;
      row[static_cast<std::size_t>(2 * other + 1)] = -m.damping[mass][other] / inertia;
    }
  }
  b_ = {0.0, gear_ratio / m.mass[0][0], 0.0, 0.0};  // input: the logged torque, tau_m = n tau
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
