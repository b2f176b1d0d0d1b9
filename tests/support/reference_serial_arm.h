// Independent generator of serial-arm logs for tests (docs/models.md#serial-robot):
// joint torques from the arm's Lagrangian, built from forward kinematics
// and geometric Jacobians (mass matrix, its numerical derivatives for the
// Coriolis terms, the potential's gradient for gravity), plus each joint's
// armature, viscous and Coulomb friction and offset. Logs as a drive
// writes them: stamps jittered and rounded to 1 ms, encoder angles
// quantised, torques with coloured (AR(1)) noise. Nothing here uses the
// library's dynamics.
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace reference {

struct ArmJoint {
  std::string name, body;
  int parent = -1;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // joint frame in the parent body's at q = 0
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // unit, in the joint frame
  double mass = 1.0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();                   // in the body frame
  Eigen::Matrix3d inertia_at_centre = Eigen::Matrix3d::Identity();   // in the body frame
  double armature = 0.0, viscous = 0.0, coulomb = 0.0, offset = 0.0;
  // Viscous friction while the motor turns backwards (NaN: `viscous`, the
  // same both ways).
  double viscous_backwards = std::numeric_limits<double>::quiet_NaN();
};

struct Arm {
  std::vector<ArmJoint> joints;
  Eigen::Vector3d gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
  // Motor angles = coupling q (empty: each joint its own motor). Joint k's
  // armature, viscous, Coulomb and offset are then motor k's, and the
  // drives add R^T (J R q'' + b R q' + c sgn(R q') + offset) per motor.
  Eigen::MatrixXd coupling;
};

/// Base yaw, shoulder and elbow pitch with offsets: a small industrial arm.
Arm ThreeJointArm();
/// The same with a three-axis wrist (pitch, roll, pitch): six joints.
Arm SixJointArm();

/// Joint torques (rigid bodies and drives) at q, q', q''.
Eigen::VectorXd ArmTorque(const Arm& arm, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                          const Eigen::VectorXd& qdd);

struct ArmLogOptions {
  double duration = 20.0, rate = 200.0;  // [s], [Hz]
  double base_frequency = 0.1;           // of the Fourier trajectory [Hz], 5 harmonics
  double amplitude = 0.8;                // [rad]
  double torque_noise = 0.3;             // innovation std of the AR(1) noise [N m]
  double noise_pole = 0.8;               // AR(1) coefficient
  double encoder_counts = 131072.0;      // per turn
  double jitter = 0.3;                   // of a sample period, uniform +-
  unsigned seed = 1;
  /// The trajectory q, q', q'' at t, in place of the built-in Fourier one
  /// (e.g. a designed trajectory under test).
  std::function<void(double t, Eigen::VectorXd& q, Eigen::VectorXd& qd, Eigen::VectorXd& qdd)> trajectory;
};

struct ArmLog {
  std::vector<double> t;
  std::vector<std::vector<double>> q, tau;  // [joint][sample]
};

ArmLog SimulateArm(const Arm& arm, const ArmLogOptions& options);

/// A controller closing the loop, as robots are identified in practice: at
/// `control_rate` the drive reads its quantised encoder (rate by backward
/// difference) and commands
///   u = tau_model(q_r, q_r', q_r'') + K_p (q_r - q_m) + K_d (q_r' - q_m'),
/// the feed-forward from a model whose masses and inertias are
/// `model_scale` of the truth (and no friction), K_p = J w^2, K_d = 2 zeta J w
/// per joint (J its inertia at the start, w = 2 pi `bandwidth`). The arm
/// integrates (RK4, `substeps` per tick) under u plus an unlogged white
/// disturbance of std `disturbance`; the log holds the commanded u plus the
/// AR(1) sensor noise of ArmLogOptions, the encoder angles and the jittered
/// stamps, at ArmLogOptions::rate (a divisor of control_rate).
struct ClosedLoopOptions {
  double control_rate = 1000.0;  // [Hz]
  int substeps = 2;
  double bandwidth = 4.0;        // [Hz]
  double damping = 0.8;          // zeta
  double model_scale = 0.85;
  double disturbance = 0.05;     // [N m]
};
ArmLog SimulateArmClosedLoop(const Arm& arm, const ArmLogOptions& options, const ClosedLoopOptions& loop);

}  // namespace reference
