#include "models/serial_dynamics.h"

#include <stdexcept>

#include <Eigen/Geometry>

namespace driveid {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

Matrix3d Skew(const Vector3d& v) {
  Matrix3d s;
  s << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return s;
}

// I w = Lift(w) (Ixx, Ixy, Ixz, Iyy, Iyz, Izz).
Eigen::Matrix<double, 3, 6> Lift(const Vector3d& w) {
  Eigen::Matrix<double, 3, 6> l;
  l << w.x(), w.y(), w.z(), 0.0, 0.0, 0.0,  //
      0.0, w.x(), 0.0, w.y(), w.z(), 0.0,   //
      0.0, 0.0, w.x(), 0.0, w.y(), w.z();
  return l;
}

// Motion of each body (in its own frame) and its pose in the parent's.
struct BodyMotion {
  Matrix3d rotation;     // R: body -> parent
  Vector3d translation;  // r: the body's origin in the parent's frame
  Vector3d w, dw, a;     // angular velocity, its rate, linear acceleration of the origin (gravity included)
};

std::vector<BodyMotion> OutwardPass(const SerialRobot& robot, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                    const Eigen::VectorXd& qdd) {
  const std::size_t n = robot.size();
  if (static_cast<std::size_t>(q.size()) != n || static_cast<std::size_t>(qd.size()) != n ||
      static_cast<std::size_t>(qdd.size()) != n) {
    throw std::logic_error("serial dynamics: q, q', q'' need one entry per joint");
  }
  std::vector<BodyMotion> m(n);
  for (std::size_t i = 0; i < n; ++i) {
    const SerialJoint& joint = robot.joints[i];
    const RigidTransform t = SerialJointTransform(joint, q(static_cast<Eigen::Index>(i)));
    BodyMotion& b = m[i];
    b.rotation = t.rotation;
    b.translation = t.translation;
    Vector3d wp = Vector3d::Zero(), dwp = Vector3d::Zero(), ap = -robot.gravity;
    if (joint.parent >= 0) {
      const BodyMotion& p = m[static_cast<std::size_t>(joint.parent)];
      wp = p.w;
      dwp = p.dw;
      ap = p.a;
    }
    const Matrix3d rt = t.rotation.transpose();
    const Vector3d& r = t.translation;
    const Vector3d& s = joint.axis;
    const double v = qd(static_cast<Eigen::Index>(i)), acc = qdd(static_cast<Eigen::Index>(i));
    const Vector3d w_in = rt * wp;
    b.a = rt * (ap + dwp.cross(r) + wp.cross(wp.cross(r)));
    if (joint.type == SerialJointType::kRevolute) {
      b.w = w_in + s * v;
      b.dw = rt * dwp + s * acc + w_in.cross(s * v);
    } else {
      b.w = w_in;
      b.dw = rt * dwp;
      b.a += 2.0 * b.w.cross(s * v) + s * acc;
    }
  }
  return m;
}

// The joint's row selector: torque = s . n (revolute) or force = s . f.
double Project(const SerialJoint& joint, const Vector3d& f, const Vector3d& n) {
  return joint.axis.dot(joint.type == SerialJointType::kRevolute ? n : f);
}

}  // namespace

RigidTransform SerialJointTransform(const SerialJoint& joint, double q) {
  RigidTransform motion;
  if (joint.type == SerialJointType::kRevolute) {
    motion.rotation = Eigen::AngleAxisd(q, joint.axis).toRotationMatrix();
  } else {
    motion.translation = joint.axis * q;
  }
  return Compose(joint.origin, motion);
}

std::vector<RigidTransform> SerialBodyPoses(const SerialRobot& robot, const Eigen::VectorXd& q) {
  std::vector<RigidTransform> poses(robot.size());
  for (std::size_t i = 0; i < robot.size(); ++i) {
    const RigidTransform local = SerialJointTransform(robot.joints[i], q(static_cast<Eigen::Index>(i)));
    const int parent = robot.joints[i].parent;
    poses[i] = parent < 0 ? local : Compose(poses[static_cast<std::size_t>(parent)], local);
  }
  return poses;
}

Eigen::VectorXd CalcSerialRigidTorque(const SerialRobot& robot, const std::vector<InertialParameters>& bodies,
                                      const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd) {
  const std::size_t n = robot.size();
  if (bodies.size() != n) throw std::logic_error("CalcSerialRigidTorque: one body per joint");
  const std::vector<BodyMotion> m = OutwardPass(robot, q, qd, qdd);
  std::vector<Vector3d> f(n), torque(n);
  for (std::size_t i = 0; i < n; ++i) {
    const InertialParameters& pi = bodies[i];
    const Vector3d h(pi[1], pi[2], pi[3]);
    const Matrix3d inertia = InertiaMatrix(pi);
    const BodyMotion& b = m[i];
    f[i] = pi[0] * b.a + b.dw.cross(h) + b.w.cross(b.w.cross(h));
    torque[i] = inertia * b.dw + b.w.cross(inertia * b.w) + h.cross(b.a);
  }
  Eigen::VectorXd tau(static_cast<Eigen::Index>(n));
  for (std::size_t k = n; k-- > 0;) {  // children come after their parents
    tau(static_cast<Eigen::Index>(k)) = Project(robot.joints[k], f[k], torque[k]);
    const int parent = robot.joints[k].parent;
    if (parent < 0) continue;
    const auto p = static_cast<std::size_t>(parent);
    const Vector3d moved = m[k].rotation * f[k];
    f[p] += moved;
    torque[p] += m[k].rotation * torque[k] + m[k].translation.cross(moved);
  }
  return tau;
}

void CalcSerialRegressor(const SerialRobot& robot, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                         const Eigen::VectorXd& qdd, Eigen::Ref<Eigen::MatrixXd> y) {
  const std::size_t n = robot.size();
  const auto rows = static_cast<Eigen::Index>(n);
  if (y.rows() != rows || y.cols() != static_cast<Eigen::Index>(kSerialColumnsPerJoint * n)) {
    throw std::logic_error("CalcSerialRegressor: y must be n x 15 n");
  }
  y.setZero();
  const std::vector<BodyMotion> m = OutwardPass(robot, q, qd, qdd);
  using Block = Eigen::Matrix<double, 3, 10>;
  for (std::size_t i = 0; i < n; ++i) {
    const BodyMotion& b = m[i];
    // The wrench of body i per unit of each of its parameters (f over n).
    Block bf = Block::Zero(), bn = Block::Zero();
    bf.col(0) = b.a;
    bf.middleCols<3>(1) = Skew(b.dw) + Skew(b.w) * Skew(b.w);
    bn.middleCols<3>(1) = -Skew(b.a);
    bn.rightCols<6>() = Lift(b.dw) + Skew(b.w) * Lift(b.w);
    const auto column = static_cast<Eigen::Index>(kSerialColumnsPerJoint * i);
    // Carried inward through every joint between body i and the base.
    for (std::size_t k = i;;) {
      const SerialJoint& joint = robot.joints[k];
      const auto row = static_cast<Eigen::Index>(k);
      y.block<1, 10>(row, column) =
          joint.axis.transpose() * (joint.type == SerialJointType::kRevolute ? bn : bf);
      if (joint.parent < 0) break;
      const Block moved = m[k].rotation * bf;
      bn = m[k].rotation * bn + Skew(m[k].translation) * moved;
      bf = moved;
      k = static_cast<std::size_t>(joint.parent);
    }
    const Eigen::Index ii = static_cast<Eigen::Index>(i);
    const std::vector<const SerialDriveTerm*>& terms = SerialDriveTerms();
    const bool coupled = robot.coupling.size() != 0;
    // The drive's motion: the joint's, or motor i's at (R q')_i, whose
    // torque reaches the joints as R_i^T.
    const double v = coupled ? robot.coupling.row(ii).dot(qd) : qd(ii);
    const double acc = coupled ? robot.coupling.row(ii).dot(qdd) : qdd(ii);
    for (std::size_t k = 0; k < terms.size(); ++k) {
      if (!terms[k]->Asked(robot.joints[i])) continue;
      const double phi = terms[k]->Column(acc, v);
      const Eigen::Index at = column + static_cast<Eigen::Index>(SerialDriveColumn(k));
      if (coupled) {
        y.col(at) = robot.coupling.row(ii).transpose() * phi;
      } else {
        y(ii, at) = phi;
      }
    }
  }
}

Eigen::MatrixXd SerialCouplingMatrix(std::size_t joints, const std::vector<std::size_t>& coupled,
                                     const Eigen::MatrixXd& block) {
  const auto n = static_cast<Eigen::Index>(joints);
  Eigen::MatrixXd r = Eigen::MatrixXd::Identity(n, n);
  for (std::size_t a = 0; a < coupled.size(); ++a) {
    for (std::size_t b = 0; b < coupled.size(); ++b) {
      r(static_cast<Eigen::Index>(coupled[a]), static_cast<Eigen::Index>(coupled[b])) =
          block(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b));
    }
  }
  return r;
}

std::vector<std::size_t> SerialCoordinates(const SerialRobot& robot) {
  std::vector<std::size_t> out;
  for (std::size_t j = 0; j < robot.size(); ++j) {
    if (robot.joints[j].mimic < 0) out.push_back(j);
  }
  return out;
}

std::vector<std::string> SerialCoordinateNames(const SerialRobot& robot) {
  std::vector<std::string> names;
  for (std::size_t j : SerialCoordinates(robot)) names.push_back(robot.joints[j].name);
  return names;
}

namespace {

// G: each joint's q per coordinate (n x m), and the offsets o (q = G q_c + o).
struct MimicMap {
  Eigen::MatrixXd g;
  Eigen::VectorXd offset;
};

MimicMap MakeMimicMap(const SerialRobot& robot) {
  const std::vector<std::size_t> coordinates = SerialCoordinates(robot);
  const auto n = static_cast<Eigen::Index>(robot.size());
  MimicMap map{Eigen::MatrixXd::Zero(n, static_cast<Eigen::Index>(coordinates.size())), Eigen::VectorXd::Zero(n)};
  std::vector<Eigen::Index> column(robot.size(), -1);
  for (std::size_t c = 0; c < coordinates.size(); ++c) {
    column[coordinates[c]] = static_cast<Eigen::Index>(c);
    map.g(static_cast<Eigen::Index>(coordinates[c]), static_cast<Eigen::Index>(c)) = 1.0;
  }
  for (std::size_t j = 0; j < robot.size(); ++j) {
    const SerialJoint& joint = robot.joints[j];
    if (joint.mimic < 0) continue;
    const auto leader = static_cast<std::size_t>(joint.mimic);
    if (leader >= robot.size() || column[leader] < 0) {
      throw std::logic_error("SerialRobot: a mimic joint's leader must be a joint that mimics none");
    }
    map.g(static_cast<Eigen::Index>(j), column[leader]) = joint.mimic_multiplier;
    map.offset(static_cast<Eigen::Index>(j)) = joint.mimic_offset;
  }
  return map;
}

}  // namespace

void ExpandSerialMotion(const SerialRobot& robot, const Eigen::VectorXd& q_c, const Eigen::VectorXd& qd_c,
                        const Eigen::VectorXd& qdd_c, Eigen::VectorXd& q, Eigen::VectorXd& qd, Eigen::VectorXd& qdd) {
  const MimicMap map = MakeMimicMap(robot);
  if (q_c.size() != map.g.cols() || qd_c.size() != map.g.cols() || qdd_c.size() != map.g.cols()) {
    throw std::logic_error("ExpandSerialMotion: one value per coordinate");
  }
  q = map.g * q_c + map.offset;
  qd = map.g * qd_c;
  qdd = map.g * qdd_c;
}

void CalcSerialCoordinateRegressor(const SerialRobot& robot, const Eigen::VectorXd& q_c, const Eigen::VectorXd& qd_c,
                                   const Eigen::VectorXd& qdd_c, Eigen::Ref<Eigen::MatrixXd> y) {
  if (static_cast<std::size_t>(q_c.size()) == robot.size()) {
    CalcSerialRegressor(robot, q_c, qd_c, qdd_c, y);
    return;
  }
  const MimicMap map = MakeMimicMap(robot);
  if (y.rows() != map.g.cols() || y.cols() != static_cast<Eigen::Index>(kSerialColumnsPerJoint * robot.size())) {
    throw std::logic_error("CalcSerialCoordinateRegressor: y must be m x 15 n");
  }
  Eigen::VectorXd q, qd, qdd;
  ExpandSerialMotion(robot, q_c, qd_c, qdd_c, q, qd, qdd);
  Eigen::MatrixXd full(static_cast<Eigen::Index>(robot.size()), y.cols());
  CalcSerialRegressor(robot, q, qd, qdd, full);
  y.noalias() = map.g.transpose() * full;
}

std::vector<std::string> SerialParameterNames(const SerialRobot& robot) {
  std::vector<std::string> names;
  for (const SerialJoint& joint : robot.joints) {
    for (const char* p : InertialParameterNames()) names.push_back(std::string(p) + "_" + joint.body);
    for (const SerialDriveTerm* term : SerialDriveTerms()) names.push_back(std::string(term->key()) + "_" + joint.name);
  }
  return names;
}

Eigen::VectorXd SerialParameterVector(const SerialRobot& robot, const std::vector<SerialDriveParameters>& drives) {
  const std::size_t n = robot.size();
  Eigen::VectorXd theta = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(kSerialColumnsPerJoint * n));
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<Eigen::Index>(kSerialColumnsPerJoint * i);
    for (std::size_t k = 0; k < kInertialParameters; ++k) theta(c + static_cast<Eigen::Index>(k)) = robot.bodies[i][k];
    if (drives.empty()) continue;
    const std::vector<const SerialDriveTerm*>& terms = SerialDriveTerms();
    for (std::size_t k = 0; k < terms.size(); ++k) {
      theta(c + static_cast<Eigen::Index>(SerialDriveColumn(k))) = drives[i].*(terms[k]->member());
    }
  }
  return theta;
}

}  // namespace driveid
