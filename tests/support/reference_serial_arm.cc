#include "support/reference_serial_arm.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Geometry>

namespace reference {
namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

struct Kinematics {
  std::vector<Matrix3d> rotation;
  std::vector<Vector3d> centre;
  std::vector<MatrixXd> jv, jw;
};

Kinematics Forward(const Arm& arm, const VectorXd& q) {
  const std::size_t n = arm.joints.size();
  Kinematics k;
  std::vector<Vector3d> origin(n), axis(n);
  for (std::size_t i = 0; i < n; ++i) {
    const ArmJoint& j = arm.joints[i];
    const Matrix3d r_parent = j.parent >= 0 ? k.rotation[static_cast<std::size_t>(j.parent)] : Matrix3d::Identity();
    const Vector3d p_parent = j.parent >= 0 ? origin[static_cast<std::size_t>(j.parent)] : Vector3d::Zero();
    const Matrix3d frame = r_parent * j.rotation;
    origin[i] = p_parent + r_parent * j.translation;
    axis[i] = frame * j.axis;
    k.rotation.push_back(frame * Eigen::AngleAxisd(q(static_cast<Eigen::Index>(i)), j.axis).toRotationMatrix());
    k.centre.push_back(origin[i] + k.rotation[i] * j.centre);
  }
  for (std::size_t i = 0; i < n; ++i) {
    MatrixXd jv = MatrixXd::Zero(3, static_cast<Eigen::Index>(n)), jw = jv;
    for (int a = static_cast<int>(i); a >= 0; a = arm.joints[static_cast<std::size_t>(a)].parent) {
      const auto s = static_cast<std::size_t>(a);
      jw.col(a) = axis[s];
      jv.col(a) = axis[s].cross(k.centre[i] - origin[s]);
    }
    k.jv.push_back(jv);
    k.jw.push_back(jw);
  }
  return k;
}

// Motor angles per joint angle: the coupling, or the identity.
MatrixXd Motors(const Arm& arm) {
  const auto n = static_cast<Eigen::Index>(arm.joints.size());
  return arm.coupling.size() == 0 ? MatrixXd(MatrixXd::Identity(n, n)) : arm.coupling;
}

MatrixXd MassMatrix(const Arm& arm, const VectorXd& q) {
  const Kinematics k = Forward(arm, q);
  const auto n = static_cast<Eigen::Index>(arm.joints.size());
  MatrixXd m = MatrixXd::Zero(n, n);
  for (std::size_t i = 0; i < arm.joints.size(); ++i) {
    const ArmJoint& j = arm.joints[i];
    const Matrix3d world = k.rotation[i] * j.inertia_at_centre * k.rotation[i].transpose();
    m += j.mass * k.jv[i].transpose() * k.jv[i] + k.jw[i].transpose() * world * k.jw[i];
  }
  const MatrixXd r = Motors(arm);
  VectorXd armature(n);
  for (Eigen::Index i = 0; i < n; ++i) armature(i) = arm.joints[static_cast<std::size_t>(i)].armature;
  m += r.transpose() * armature.asDiagonal() * r;
  return m;
}

double Potential(const Arm& arm, const VectorXd& q) {
  const Kinematics k = Forward(arm, q);
  double v = 0.0;
  for (std::size_t i = 0; i < arm.joints.size(); ++i) v -= arm.joints[i].mass * arm.gravity.dot(k.centre[i]);
  return v;
}

}  // namespace

Arm ThreeJointArm() {
  Arm arm;
  ArmJoint yaw;
  yaw.name = "yaw";
  yaw.body = "turret";
  yaw.translation = Vector3d(0.0, 0.0, 0.3);
  yaw.mass = 6.0;
  yaw.centre = Vector3d(0.02, 0.01, 0.08);
  yaw.inertia_at_centre = Vector3d(0.06, 0.05, 0.04).asDiagonal();
  yaw.armature = 0.4;
  yaw.viscous = 3.0;
  yaw.coulomb = 2.0;
  yaw.offset = 0.3;
  ArmJoint shoulder;
  shoulder.name = "shoulder";
  shoulder.body = "upper";
  shoulder.parent = 0;
  shoulder.translation = Vector3d(0.05, 0.0, 0.12);
  shoulder.rotation = Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitX()).toRotationMatrix();
  shoulder.mass = 4.0;
  shoulder.centre = Vector3d(0.25, 0.0, 0.03);
  shoulder.inertia_at_centre = Vector3d(0.01, 0.09, 0.09).asDiagonal();
  shoulder.armature = 0.6;
  shoulder.viscous = 4.0;
  shoulder.coulomb = 3.0;
  shoulder.offset = -0.5;
  ArmJoint elbow;
  elbow.name = "elbow";
  elbow.body = "fore";
  elbow.parent = 1;
  elbow.translation = Vector3d(0.5, 0.0, 0.0);
  elbow.mass = 2.0;
  elbow.centre = Vector3d(0.2, 0.02, 0.0);
  elbow.inertia_at_centre = Vector3d(0.005, 0.04, 0.04).asDiagonal();
  elbow.armature = 0.2;
  elbow.viscous = 1.5;
  elbow.coulomb = 1.0;
  elbow.offset = 0.1;
  arm.joints = {yaw, shoulder, elbow};
  return arm;
}

Arm SixJointArm() {
  Arm arm = ThreeJointArm();
  const struct {
    const char* name;
    const char* body;
    Vector3d translation, axis, centre;
    double mass, armature, viscous, coulomb;
  } wrist[3] = {{"wrist1", "w1", Vector3d(0.45, 0.0, 0.0), Vector3d::UnitZ(), Vector3d(0.0, 0.03, 0.02), 1.2, 0.1, 0.8, 0.5},
                {"wrist2", "w2", Vector3d(0.0, 0.1, 0.0), Vector3d::UnitY(), Vector3d(0.01, 0.0, 0.04), 0.9, 0.08, 0.6, 0.4},
                {"wrist3", "w3", Vector3d(0.0, 0.0, 0.1), Vector3d::UnitZ(), Vector3d(0.0, 0.01, 0.03), 0.4, 0.05, 0.5, 0.3}};
  for (int i = 0; i < 3; ++i) {
    ArmJoint j;
    j.name = wrist[i].name;
    j.body = wrist[i].body;
    j.parent = static_cast<int>(arm.joints.size()) - 1;
    j.translation = wrist[i].translation;
    j.axis = wrist[i].axis;
    j.mass = wrist[i].mass;
    j.centre = wrist[i].centre;
    j.inertia_at_centre = Vector3d(0.004, 0.005, 0.003).asDiagonal() * (1.0 + i);
    j.armature = wrist[i].armature;
    j.viscous = wrist[i].viscous;
    j.coulomb = wrist[i].coulomb;
    j.offset = 0.05 * (i - 1);
    arm.joints.push_back(j);
  }
  return arm;
}

// tau = M q'' + sum_jk (dM_ij/dq_k - 1/2 dM_jk/dq_i) q'_j q'_k + dV/dq_i + drives.
VectorXd ArmTorque(const Arm& arm, const VectorXd& q, const VectorXd& qd, const VectorXd& qdd) {
  const auto n = static_cast<Eigen::Index>(arm.joints.size());
  const double h = 1e-6;
  std::vector<MatrixXd> dm(static_cast<std::size_t>(n));
  VectorXd dv(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    VectorXd up = q, down = q;
    up(k) += h;
    down(k) -= h;
    dm[static_cast<std::size_t>(k)] = (MassMatrix(arm, up) - MassMatrix(arm, down)) / (2.0 * h);
    dv(k) = (Potential(arm, up) - Potential(arm, down)) / (2.0 * h);
  }
  VectorXd tau = MassMatrix(arm, q) * qdd + dv;
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) {
      for (Eigen::Index k = 0; k < n; ++k) {
        tau(i) += (dm[static_cast<std::size_t>(k)](i, j) - 0.5 * dm[static_cast<std::size_t>(i)](j, k)) * qd(j) * qd(k);
      }
    }
  }
  // The motors' friction and offsets, each on its own rate, back to the joints.
  const MatrixXd r = Motors(arm);
  const VectorXd motor_rate = r * qd;
  VectorXd motor(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const ArmJoint& joint = arm.joints[static_cast<std::size_t>(i)];
    const double v = motor_rate(i);
    const double b = v < 0.0 && !std::isnan(joint.viscous_backwards) ? joint.viscous_backwards : joint.viscous;
    motor(i) = b * v + joint.coulomb * ((v > 0) - (v < 0)) + joint.offset;
  }
  tau += r.transpose() * motor;
  return tau;
}

namespace {

// The built-in reference: a Fourier trajectory per joint whose
// coefficients are fixed (seed 99), so every log excites the arm alike and
// only the noise differs; or the options' own trajectory.
class Reference {
 public:
  Reference(std::size_t joints, const ArmLogOptions& o) : o_(o), a_(joints, std::vector<double>(kHarmonics)), b_(a_) {
    std::mt19937 shape(99);
    std::uniform_real_distribution<double> coefficient(-1.0, 1.0);
    for (std::size_t j = 0; j < joints; ++j) {
      for (int l = 0; l < kHarmonics; ++l) {
        a_[j][static_cast<std::size_t>(l)] = o.amplitude * coefficient(shape) / (l + 1);
        b_[j][static_cast<std::size_t>(l)] = o.amplitude * coefficient(shape) / (l + 1);
      }
    }
  }
  void At(double t, VectorXd& q, VectorXd& qd, VectorXd& qdd) const {
    if (o_.trajectory) {
      o_.trajectory(t, q, qd, qdd);
      return;
    }
    for (std::size_t j = 0; j < a_.size(); ++j) {
      double p = 0.0, v = 0.0, acc = 0.0;
      for (int l = 0; l < kHarmonics; ++l) {
        const double w = 2.0 * M_PI * o_.base_frequency * (l + 1);
        const double al = a_[j][static_cast<std::size_t>(l)], bl = b_[j][static_cast<std::size_t>(l)];
        p += al * std::sin(w * t) + bl * (std::cos(w * t) - 1.0);
        v += w * (al * std::cos(w * t) - bl * std::sin(w * t));
        acc += -w * w * (al * std::sin(w * t) + bl * std::cos(w * t));
      }
      q(static_cast<Eigen::Index>(j)) = p;
      qd(static_cast<Eigen::Index>(j)) = v;
      qdd(static_cast<Eigen::Index>(j)) = acc;
    }
  }

 private:
  static constexpr int kHarmonics = 5;
  const ArmLogOptions& o_;
  std::vector<std::vector<double>> a_, b_;
};

// Stamped to 1 ms (to a tenth of the period above 500 Hz, where 1 ms would repeat stamps).
double Stamp(double t, double rate) {
  const double stamp = rate <= 500.0 ? 1e-3 : 0.1 / rate;
  return std::round(t / stamp) * stamp;
}

}  // namespace

ArmLog SimulateArm(const Arm& arm, const ArmLogOptions& o) {
  const std::size_t n = arm.joints.size();
  std::mt19937 rng(o.seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::normal_distribution<double> normal;
  const Reference reference(n, o);
  ArmLog log;
  log.q.assign(n, {});
  log.tau.assign(n, {});
  std::vector<double> noise(n, 0.0);
  const double period = 1.0 / o.rate, count = o.encoder_counts / (2.0 * M_PI);
  for (int k = 0; k * period <= o.duration; ++k) {
    const double t = k * period + o.jitter * period * uniform(rng);
    VectorXd q(static_cast<Eigen::Index>(n)), qd = q, qdd = q;
    reference.At(t, q, qd, qdd);
    const VectorXd tau = ArmTorque(arm, q, qd, qdd);
    log.t.push_back(Stamp(t, o.rate));
    for (std::size_t j = 0; j < n; ++j) {
      noise[j] = o.noise_pole * noise[j] + o.torque_noise * normal(rng);
      log.q[j].push_back(std::round(q(static_cast<Eigen::Index>(j)) * count) / count);
      log.tau[j].push_back(tau(static_cast<Eigen::Index>(j)) + noise[j]);
    }
  }
  return log;
}

ArmLog SimulateArmClosedLoop(const Arm& arm, const ArmLogOptions& o, const ClosedLoopOptions& loop) {
  const std::size_t n = arm.joints.size();
  const auto size = static_cast<Eigen::Index>(n);
  std::mt19937 rng(o.seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::normal_distribution<double> normal;
  const Reference reference(n, o);
  Arm model = arm;  // the controller's model: masses and inertias off, no friction
  for (ArmJoint& j : model.joints) {
    j.mass *= loop.model_scale;
    j.inertia_at_centre *= loop.model_scale;
    j.armature *= loop.model_scale;
    j.viscous = j.coulomb = j.offset = 0.0;
  }
  VectorXd q(size), qd(size), qdd(size), qr(size), qdr(size), qddr(size);
  reference.At(0.0, q, qd, qdd);
  const VectorXd inertia = MassMatrix(arm, q).diagonal();
  const double w = 2.0 * M_PI * loop.bandwidth, h = 1.0 / loop.control_rate / loop.substeps;
  const VectorXd kp = inertia * w * w, kd = inertia * 2.0 * loop.damping * w;
  // q'' = M(q)^-1 (u - (C q' + g + friction)(q, q')): ArmTorque at q'' = 0 is the rest.
  const auto accel = [&](const VectorXd& x, const VectorXd& v, const VectorXd& u) -> VectorXd {
    return MassMatrix(arm, x).ldlt().solve(u - ArmTorque(arm, x, v, VectorXd::Zero(size)));
  };
  const double count = o.encoder_counts / (2.0 * M_PI);
  const auto encoder = [&](const VectorXd& x) {
    VectorXd m(size);
    for (Eigen::Index j = 0; j < size; ++j) m(j) = std::round(x(j) * count) / count;
    return m;
  };
  const long per_log = std::max(1L, std::lround(loop.control_rate / o.rate));
  ArmLog log;
  log.q.assign(n, {});
  log.tau.assign(n, {});
  std::vector<double> noise(n, 0.0);
  VectorXd measured = encoder(q), previous = measured;
  for (long tick = 0; static_cast<double>(tick) / loop.control_rate <= o.duration; ++tick) {
    const double t = static_cast<double>(tick) / loop.control_rate;
    reference.At(t, qr, qdr, qddr);
    measured = encoder(q);
    const VectorXd rate = (measured - previous) * loop.control_rate;
    previous = measured;
    const VectorXd u = ArmTorque(model, qr, qdr, qddr) + kp.cwiseProduct(qr - measured) + kd.cwiseProduct(qdr - rate);
    if (tick % per_log == 0) {
      log.t.push_back(Stamp(t + o.jitter / o.rate * uniform(rng), o.rate));
      for (std::size_t j = 0; j < n; ++j) {
        noise[j] = o.noise_pole * noise[j] + o.torque_noise * normal(rng);
        log.q[j].push_back(measured(static_cast<Eigen::Index>(j)));
        log.tau[j].push_back(u(static_cast<Eigen::Index>(j)) + noise[j]);
      }
    }
    VectorXd applied = u;
    for (Eigen::Index j = 0; j < size; ++j) applied(j) += loop.disturbance * normal(rng);
    for (int s = 0; s < loop.substeps; ++s) {  // RK4 under the held torque
      const VectorXd a1 = accel(q, qd, applied);
      const VectorXd a2 = accel(q + 0.5 * h * qd, qd + 0.5 * h * a1, applied);
      const VectorXd a3 = accel(q + 0.5 * h * (qd + 0.5 * h * a1), qd + 0.5 * h * a2, applied);
      const VectorXd a4 = accel(q + h * (qd + 0.5 * h * a2), qd + h * a3, applied);
      q += h * qd + h * h / 6.0 * (a1 + a2 + a3);
      qd += h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
    }
  }
  return log;
}

}  // namespace reference
