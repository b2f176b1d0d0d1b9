// The serial robot's inverse dynamics and regressor (models/serial_dynamics.h)
// against what is derived here without Newton-Euler: the Lagrangian of a
// four-joint arm (revolute and prismatic joints, tilted axes, full inertia
// tensors) from its geometric Jacobians, differentiated numerically; the
// closed-form torques of a planar two-link arm; and energy (power = q' . tau).
#include <cmath>
#include <random>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include "models/serial_dynamics.h"
#include "models/serial_robot.h"

using namespace driveid;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;

namespace {

Matrix3d RandomInertia(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.05, 0.4), angle(-3.0, 3.0);
  const Matrix3d r = RotationFromRpy(angle(rng), angle(rng), angle(rng));
  const double a = u(rng), b = u(rng);
  const Vector3d principal(a, b, std::min(a + b, 0.3 + 0.5 * (a + b)) * 0.9);  // triangle inequality
  return r * principal.asDiagonal() * r.transpose();
}

SerialRobot FourJointArm() {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  SerialRobot robot;
  robot.gravity = Vector3d(0.3, -0.2, -9.81);
  const Vector3d axes[4] = {Vector3d::UnitZ(), Vector3d::UnitY(), Vector3d(1, 0, 0),
                            Vector3d(0.3, -0.5, 0.8).normalized()};
  const SerialJointType types[4] = {SerialJointType::kRevolute, SerialJointType::kRevolute,
                                    SerialJointType::kPrismatic, SerialJointType::kRevolute};
  for (int i = 0; i < 4; ++i) {
    SerialJoint j;
    j.name = "j" + std::to_string(i + 1);
    j.body = "link" + std::to_string(i + 1);
    j.type = types[i];
    j.parent = i - 1;
    j.origin.rotation = RotationFromRpy(u(rng), u(rng), u(rng));
    j.origin.translation = Vector3d(u(rng), u(rng), 0.4 + u(rng));
    j.axis = axes[i];
    robot.joints.push_back(j);
    const double mass = 1.0 + 2.0 * std::abs(u(rng));
    robot.bodies.push_back(InertialFromCentre(mass, Vector3d(u(rng), u(rng), u(rng)), RandomInertia(rng)));
  }
  return robot;
}

// World poses and the geometric Jacobians of each body's centre of mass,
// from the joint definitions alone.
struct Kinematics {
  std::vector<Matrix3d> rotation;
  std::vector<Vector3d> centre;
  std::vector<Eigen::MatrixXd> jv, jw;  // 3 x n each
};

Kinematics Forward(const SerialRobot& robot, const VectorXd& q) {
  const std::size_t n = robot.size();
  Kinematics k;
  std::vector<Vector3d> origin(n), axis(n);
  for (std::size_t i = 0; i < n; ++i) {
    const SerialJoint& j = robot.joints[i];
    Matrix3d r_parent = Matrix3d::Identity();
    Vector3d p_parent = Vector3d::Zero();
    if (j.parent >= 0) {
      r_parent = k.rotation[static_cast<std::size_t>(j.parent)];
      p_parent = origin[static_cast<std::size_t>(j.parent)];
    }
    const Matrix3d joint_frame = r_parent * j.origin.rotation;
    const Vector3d joint_origin = p_parent + r_parent * j.origin.translation;
    axis[i] = joint_frame * j.axis;
    if (j.type == SerialJointType::kRevolute) {
      k.rotation.push_back(joint_frame * Eigen::AngleAxisd(q(i), j.axis).toRotationMatrix());
      origin[i] = joint_origin;
    } else {
      k.rotation.push_back(joint_frame);
      origin[i] = joint_origin + axis[i] * q(i);
    }
    const InertialParameters& pi = robot.bodies[i];
    k.centre.push_back(origin[i] + k.rotation[i] * Vector3d(pi[1], pi[2], pi[3]) / pi[0]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::MatrixXd jv = Eigen::MatrixXd::Zero(3, static_cast<Eigen::Index>(n)), jw = jv;
    for (int a = static_cast<int>(i); a >= 0; a = robot.joints[static_cast<std::size_t>(a)].parent) {
      const auto s = static_cast<std::size_t>(a);
      // The joint's own point: where its axis passes (its frame's origin).
      const SerialJoint& j = robot.joints[s];
      const Vector3d on_axis = robot.joints[s].type == SerialJointType::kRevolute ? origin[s] : Vector3d::Zero();
      if (j.type == SerialJointType::kRevolute) {
        jw.col(a) = axis[s];
        jv.col(a) = axis[s].cross(k.centre[i] - on_axis);
      } else {
        jv.col(a) = axis[s];
      }
    }
    k.jv.push_back(jv);
    k.jw.push_back(jw);
  }
  return k;
}

Eigen::MatrixXd MassMatrix(const SerialRobot& robot, const VectorXd& q) {
  const Kinematics k = Forward(robot, q);
  const auto n = static_cast<Eigen::Index>(robot.size());
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t i = 0; i < robot.size(); ++i) {
    const InertialParameters& pi = robot.bodies[i];
    const Vector3d c(pi[1] / pi[0], pi[2] / pi[0], pi[3] / pi[0]);
    const Matrix3d at_centre = InertiaMatrix(pi) - pi[0] * (c.squaredNorm() * Matrix3d::Identity() - c * c.transpose());
    const Matrix3d world = k.rotation[i] * at_centre * k.rotation[i].transpose();
    m += pi[0] * k.jv[i].transpose() * k.jv[i] + k.jw[i].transpose() * world * k.jw[i];
  }
  return m;
}

double Potential(const SerialRobot& robot, const VectorXd& q) {
  const Kinematics k = Forward(robot, q);
  double v = 0.0;
  for (std::size_t i = 0; i < robot.size(); ++i) v -= robot.bodies[i][0] * robot.gravity.dot(k.centre[i]);
  return v;
}

// tau = M q'' + sum_jk (dM_ij/dq_k - 1/2 dM_jk/dq_i) q'_j q'_k + dV/dq_i.
VectorXd LagrangeTorque(const SerialRobot& robot, const VectorXd& q, const VectorXd& qd, const VectorXd& qdd) {
  const auto n = static_cast<Eigen::Index>(robot.size());
  const double h = 1e-6;
  std::vector<Eigen::MatrixXd> dm(static_cast<std::size_t>(n));
  VectorXd dv(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    VectorXd up = q, down = q;
    up(k) += h;
    down(k) -= h;
    dm[static_cast<std::size_t>(k)] = (MassMatrix(robot, up) - MassMatrix(robot, down)) / (2.0 * h);
    dv(k) = (Potential(robot, up) - Potential(robot, down)) / (2.0 * h);
  }
  VectorXd tau = MassMatrix(robot, q) * qdd + dv;
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) {
      for (Eigen::Index k = 0; k < n; ++k) {
        tau(i) += (dm[static_cast<std::size_t>(k)](i, j) - 0.5 * dm[static_cast<std::size_t>(i)](j, k)) * qd(j) * qd(k);
      }
    }
  }
  return tau;
}

}  // namespace

TEST_CASE("serial RNEA equals the Lagrangian of a four-joint arm (revolute, prismatic, tilted axes)") {
  const SerialRobot robot = FourJointArm();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  for (int trial = 0; trial < 10; ++trial) {
    VectorXd q(4), qd(4), qdd(4);
    for (int i = 0; i < 4; ++i) {
      q(i) = u(rng);
      qd(i) = u(rng);
      qdd(i) = u(rng);
    }
    const VectorXd rnea = CalcSerialRigidTorque(robot, robot.bodies, q, qd, qdd);
    const VectorXd lagrange = LagrangeTorque(robot, q, qd, qdd);
    INFO("rnea " << rnea.transpose() << "\nlagrange " << lagrange.transpose());
    CHECK((rnea - lagrange).norm() <= 1e-6 * (1.0 + lagrange.norm()));
  }
}

TEST_CASE("serial regressor times the parameters is the RNEA torque plus the drives") {
  SerialRobot robot = FourJointArm();
  std::vector<SerialDriveParameters> drives = {{0.3, 1.1, 0.7, -0.2}, {0.5, 2.0, 1.4, 0.1},
                                               {0.05, 4.0, 3.0, 0.5}, {0.1, 0.4, 0.2, 0.0}};
  // The second joint's viscous friction per direction: 2.6 forwards, 1.4 back.
  robot.joints[1].viscous_per_direction = true;
  drives[1].viscous_asymmetry = 0.6;
  const double forwards[4] = {1.1, 2.6, 4.0, 0.4}, backwards[4] = {1.1, 1.4, 4.0, 0.4};
  const VectorXd theta = SerialParameterVector(robot, drives);
  REQUIRE(SerialParameterNames(robot).size() == 60);
  CHECK(SerialParameterNames(robot)[10] == "armature_j1");
  CHECK(SerialParameterNames(robot)[14] == "viscous_asymmetry_j1");
  CHECK(SerialParameterNames(robot)[15] == "m_link2");
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  Eigen::MatrixXd y(4, 60);
  for (int trial = 0; trial < 20; ++trial) {
    VectorXd q(4), qd(4), qdd(4);
    for (int i = 0; i < 4; ++i) {
      q(i) = u(rng);
      qd(i) = u(rng);
      qdd(i) = u(rng);
    }
    CalcSerialRegressor(robot, q, qd, qdd, y);
    VectorXd expected = CalcSerialRigidTorque(robot, robot.bodies, q, qd, qdd);
    for (int i = 0; i < 4; ++i) {
      const auto& d = drives[static_cast<std::size_t>(i)];
      const double b = qd(i) > 0.0 ? forwards[i] : backwards[i];
      expected(i) += d.armature * qdd(i) + b * qd(i) + d.coulomb * ((qd(i) > 0) - (qd(i) < 0)) + d.offset;
    }
    CHECK((y * theta - expected).norm() <= 1e-10 * (1.0 + expected.norm()));
    // Joints that do not ask for it have no asymmetry column.
    CHECK(y.col(3 * 15 - 1).norm() == 0.0);
  }
}

TEST_CASE("serial RNEA: a planar two-link arm's closed form") {
  const double m1 = 2.0, m2 = 1.3, l1 = 0.7, c1 = 0.3, c2 = 0.25, i1 = 0.04, i2 = 0.02, g = 9.81;
  SerialRobot robot;
  robot.gravity = Vector3d(0.0, -g, 0.0);  // the arm moves in the x-y plane, gravity along -y
  SerialJoint a;
  a.name = "a";
  a.body = "one";
  robot.joints.push_back(a);
  SerialJoint b = a;
  b.name = "b";
  b.body = "two";
  b.parent = 0;
  b.origin.translation = Vector3d(l1, 0.0, 0.0);
  robot.joints.push_back(b);
  Matrix3d ia = Matrix3d::Identity() * 0.01, ib = ia;
  ia(2, 2) = i1;
  ib(2, 2) = i2;
  robot.bodies = {InertialFromCentre(m1, Vector3d(c1, 0, 0), ia), InertialFromCentre(m2, Vector3d(c2, 0, 0), ib)};
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int trial = 0; trial < 10; ++trial) {
    VectorXd q(2), qd(2), qdd(2);
    for (int i = 0; i < 2; ++i) {
      q(i) = u(rng);
      qd(i) = u(rng);
      qdd(i) = u(rng);
    }
    const double cos2 = std::cos(q(1)), sin2 = std::sin(q(1));
    const double m11 = i1 + i2 + m1 * c1 * c1 + m2 * (l1 * l1 + c2 * c2 + 2 * l1 * c2 * cos2);
    const double m12 = i2 + m2 * (c2 * c2 + l1 * c2 * cos2), m22 = i2 + m2 * c2 * c2;
    const double hh = m2 * l1 * c2 * sin2;
    const double g1 = (m1 * c1 + m2 * l1) * g * std::cos(q(0)) + m2 * c2 * g * std::cos(q(0) + q(1));
    const double g2 = m2 * c2 * g * std::cos(q(0) + q(1));
    const double tau1 = m11 * qdd(0) + m12 * qdd(1) - hh * (2 * qd(0) * qd(1) + qd(1) * qd(1)) + g1;
    const double tau2 = m12 * qdd(0) + m22 * qdd(1) + hh * qd(0) * qd(0) + g2;
    const VectorXd tau = CalcSerialRigidTorque(robot, robot.bodies, q, qd, qdd);
    CHECK(tau(0) == Approx(tau1).epsilon(1e-12).margin(1e-12));
    CHECK(tau(1) == Approx(tau2).epsilon(1e-12).margin(1e-12));
  }
}

TEST_CASE("serial RNEA: the power q' . tau is the rate of the arm's energy") {
  const SerialRobot robot = FourJointArm();
  VectorXd q(4), qd(4), qdd(4);
  q << 0.3, -0.7, 0.2, 1.1;
  qd << 0.9, -0.4, 0.6, -1.2;
  qdd << -0.5, 0.8, 0.3, 0.2;
  const auto energy = [&](double t) {
    const VectorXd qt = q + qd * t + 0.5 * qdd * t * t, vt = qd + qdd * t;
    return 0.5 * vt.dot(MassMatrix(robot, qt) * vt) + Potential(robot, qt);
  };
  const double h = 1e-5;
  const double rate = (energy(h) - energy(-h)) / (2.0 * h);
  const VectorXd tau = CalcSerialRigidTorque(robot, robot.bodies, q, qd, qdd);
  CHECK(qd.dot(tau) == Approx(rate).epsilon(1e-7));
}

TEST_CASE("inertial parameters moved between frames keep mass, centre and inertia") {
  std::mt19937 rng(21);
  const Matrix3d inertia = RandomInertia(rng);
  const InertialParameters pi = InertialFromCentre(2.5, Vector3d(0.1, -0.2, 0.3), inertia);
  RigidTransform t;
  t.rotation = RotationFromRpy(0.4, -1.1, 2.0);
  t.translation = Vector3d(0.5, 0.2, -0.7);
  const InertialParameters moved = TransformInertial(pi, t);
  const Vector3d centre = t.rotation * Vector3d(0.1, -0.2, 0.3) + t.translation;
  const InertialParameters expected = InertialFromCentre(2.5, centre, t.rotation * inertia * t.rotation.transpose());
  for (std::size_t k = 0; k < kInertialParameters; ++k) CHECK(moved[k] == Approx(expected[k]).margin(1e-12));
}

TEST_CASE("serial coordinates: with a mimic joint the power q_c' . tau_c is the rate of the arm's energy") {
  // Joint 3 follows joint 2 at -0.7 q_2 + 0.3 (a linkage): three coordinates.
  SerialRobot robot = FourJointArm();
  robot.joints[2].mimic = 1;
  robot.joints[2].mimic_multiplier = -0.7;
  robot.joints[2].mimic_offset = 0.3;
  REQUIRE(SerialCoordinates(robot) == std::vector<std::size_t>{0, 1, 3});
  VectorXd qc(3), qdc(3), qddc(3);
  qc << 0.3, -0.7, 1.1;
  qdc << 0.9, -0.4, -1.2;
  qddc << -0.5, 0.8, 0.2;
  // The full motion written out here, independently of ExpandSerialMotion.
  const auto full = [](const VectorXd& c, double offset) {
    VectorXd q(4);
    q << c(0), c(1), -0.7 * c(1) + offset, c(2);
    return q;
  };
  const auto energy = [&](double t) {
    const VectorXd qt = full(qc + qdc * t + 0.5 * qddc * t * t, 0.3), vt = full(qdc + qddc * t, 0.0);
    return 0.5 * vt.dot(MassMatrix(robot, qt) * vt) + Potential(robot, qt);
  };
  const double h = 1e-5;
  const double rate = (energy(h) - energy(-h)) / (2.0 * h);
  Eigen::MatrixXd y(3, 60);
  CalcSerialCoordinateRegressor(robot, qc, qdc, qddc, y);
  const VectorXd tau = y * SerialParameterVector(robot, {});
  CHECK(qdc.dot(tau) == Approx(rate).epsilon(1e-7));
  // A mimic joint's drive acts through its multiplier: viscous b on its own
  // rate -0.7 q_2' reaches joint 2 as -0.7 b (-0.7 q_2').
  std::vector<SerialDriveParameters> drives(4);
  drives[2].viscous = 2.0;
  const VectorXd with = y * SerialParameterVector(robot, drives);
  CHECK(with(1) - tau(1) == Approx(0.49 * 2.0 * qdc(1)));
  CHECK(with(0) == Approx(tau(0)));
}
