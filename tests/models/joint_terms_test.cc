// The joint's terms (models/joint_term.h) against the two-mass equations
// written out by hand from docs/models.md#elastic-joint: the regressors the
// registry assembles from the terms' columns reproduce the motor, total and
// sensor equations at random motions; the linear terms' matrices are
// symmetric with the spring loading only the deflection; and the frequency
// response's log-gradients agree with central differences.
#include <cmath>
#include <complex>
#include <random>

#include <catch2/catch.hpp>

#include "models/joint.h"
#include "models/joint_term.h"

using namespace driveid;

namespace {

JointParameters Example() {
  JointParameters p;
  p.motor_inertia = 0.031;
  p.link_inertia = 0.42;
  p.stiffness = 950.0;
  p.damping = 0.7;
  p.motor_viscous = 0.11;
  p.motor_coulomb = 0.35;
  p.link_viscous = 0.05;
  p.link_coulomb = 0.21;
  p.offset = -0.08;
  p.gravity_cos = 1.3;
  p.gravity_sin = -0.4;
  p.link_torque_offset = 0.02;
  return p;
}

double Sgn(double x) { return (x > 0.0) - (x < 0.0); }

double Dot(const std::array<double, kJointTerms>& phi, const JointParameters& p) {
  double sum = 0.0;
  for (std::size_t j = 0; j < kJointTerms; ++j) sum += phi[j] * ModelValue(JointParameterTable()[j], p);
  return sum;
}

}  // namespace

TEST_CASE("joint regressors from the terms reproduce the motor, total and sensor equations") {
  const JointParameters p = Example();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int trial = 0; trial < 50; ++trial) {
    const double qm = u(rng), vm = u(rng), am = u(rng), ql = u(rng), vl = u(rng), al = u(rng);
    const JointRegressors r = CalcJointRegressors(qm, vm, am, ql, vl, al);
    const double d = qm - ql, dd = vm - vl;
    const double motor = p.motor_inertia * am + p.stiffness * d + p.damping * dd + p.motor_viscous * vm +
                         p.motor_coulomb * Sgn(vm) + p.offset;
    const double total = p.motor_inertia * am + p.link_inertia * al + p.motor_viscous * vm + p.motor_coulomb * Sgn(vm) +
                         p.link_viscous * vl + p.link_coulomb * Sgn(vl) + p.offset + p.gravity_cos * std::cos(ql) +
                         p.gravity_sin * std::sin(ql);
    const double sensor = p.stiffness * d + p.damping * dd + p.link_torque_offset;
    CHECK(Dot(r.motor, p) == Approx(motor).epsilon(1e-12));
    CHECK(Dot(r.total, p) == Approx(total).epsilon(1e-12));
    CHECK(Dot(r.link, p) == Approx(sensor).epsilon(1e-12));
  }
}

TEST_CASE("joint terms: every parameter row belongs to one term, linear rows are the response's six") {
  const auto& table = JointParameterTable();
  REQUIRE(table.size() == kJointTerms + 2);  // + gear_ratio, k_t
  for (std::size_t j = 0; j < kJointTerms; ++j) {
    const JointTermParameter& tp = JointParameterTerm(j);
    REQUIRE(tp.term != nullptr);
    CHECK(tp.term->Rows().at(tp.row).spec.key == table[j].spec.key);
  }
  const std::vector<std::size_t> expected = {0, 1, 2, 3, 4, 6};  // J_m, J_l, k, d, b_m, b_l
  CHECK(JointLinearParameters() == expected);
  CHECK(table[6].in_model == &JointParameters::link_viscous);
}

TEST_CASE("joint linear dynamics: symmetric matrices, the spring loads only the deflection") {
  const JointParameters p = Example();
  const JointLinearDynamics m = CalcJointLinearDynamics(p);
  CHECK(m.mass[0][0] == p.motor_inertia);
  CHECK(m.mass[1][1] == p.link_inertia);
  CHECK(m.mass[0][1] == 0.0);
  CHECK(m.stiffness[0][1] == m.stiffness[1][0]);
  CHECK(m.damping[0][1] == m.damping[1][0]);
  // A rigid rotation (theta_m = theta_l) stores no energy: K (1, 1) = 0.
  CHECK(m.stiffness[0][0] + m.stiffness[0][1] == Approx(0.0).margin(1e-12));
  CHECK(m.stiffness[1][0] + m.stiffness[1][1] == Approx(0.0).margin(1e-12));
  CHECK(m.damping[0][0] == Approx(p.damping + p.motor_viscous));
  CHECK(m.damping[1][1] == Approx(p.damping + p.link_viscous));
}

TEST_CASE("joint response: closed form and log-gradients by central differences") {
  const JointParameters p = Example();
  const double n = 9.0;
  for (const double omega : {3.0, 47.0, 160.0, 900.0}) {
    const JointResponse r = CalcJointResponse(p, n, omega, ResponseQuantity::kPosition);
    // By hand: A_m, A_l, K and Delta of the header.
    const std::complex<double> s(0.0, omega);
    const auto spring = p.damping * s + p.stiffness;
    const auto a_m = p.motor_inertia * s * s + p.motor_viscous * s + spring;
    const auto a_l = p.link_inertia * s * s + p.link_viscous * s + spring;
    const auto delta = a_m * a_l - spring * spring;
    CHECK(std::abs(r.motor - n * n * a_l / delta) <= 1e-12 * std::abs(r.motor));
    CHECK(std::abs(r.link - n * spring / delta) <= 1e-12 * std::abs(r.link));
    const std::vector<std::size_t>& linear = JointLinearParameters();
    for (std::size_t i = 0; i < linear.size(); ++i) {
      JointParameters up = p, down = p;
      const auto& row = JointParameterTable()[linear[i]];
      const double h = 1e-6 * ModelValue(row, p);
      ModelValue(row, up) += h;
      ModelValue(row, down) -= h;
      const JointResponse ru = CalcJointResponse(up, n, omega, ResponseQuantity::kPosition);
      const JointResponse rd = CalcJointResponse(down, n, omega, ResponseQuantity::kPosition);
      const auto motor = (std::log(ru.motor) - std::log(rd.motor)) / (2.0 * h);
      const auto link = (std::log(ru.link) - std::log(rd.link)) / (2.0 * h);
      INFO(row.spec.key << " at " << omega);
      CHECK(std::abs(r.motor_log_gradient[i] - motor) <= 1e-5 * std::abs(motor) + 1e-7);
      CHECK(std::abs(r.link_log_gradient[i] - link) <= 1e-5 * std::abs(link) + 1e-7);
    }
  }
}
