// A serial robot of rigid links on a fixed base (docs/models.md#serial-robot):
// a tree of revolute and prismatic joints as a URDF describes it, each
// joint moving one body (the links it carries rigidly, merged). Frames:
// body i's frame is its joint's child frame; at q_i = 0 it sits at the
// joint's `origin` in the parent body's frame (the base's for a root
// joint), and the joint turns it by q_i [rad] about `axis` or shifts it by
// q_i [m] along it (a unit vector in body i's frame, fixed in both).
//
// Inertial parameters, the 10 standard ones per body in its own frame,
// linear in the dynamics (Atkeson, An and Hollerbach 1986):
//   pi = (m, h_x, h_y, h_z, I_xx, I_xy, I_xz, I_yy, I_yz, I_zz),
// m [kg] the mass, h = m c [kg m] the first moment (c the centre of mass),
// I [kg m^2] the inertia about the frame's origin (not the centre of mass):
//   I = I_c + m (|c|^2 1 - c c^T).
// Per joint, the drive (referred to the joint): armature J_a [kg m^2 or kg]
// (rotor inertia times the gear ratio squared), viscous b [N m s/rad],
// Coulomb friction tau_c [N m] and an offset tau_0 [N m]:
//   tau_i = (rigid-body torque)_i + J_a q_i'' + b q_i' + tau_c sgn q_i' + tau_0,
// and where asked (SerialJoint::viscous_per_direction) viscous friction per
// direction, b+ = b + d for q_i' > 0 and b- = b - d below, i.e. + d |q_i'|
// (d the viscous asymmetry [N m s/rad]). Coulomb friction per direction,
// tau_c+ [q' > 0] - tau_c- [q' < 0], is tau_c sgn q' plus an offset while
// the joint moves: the offset (docs/models.md#serial-robot).
// Coupled drives (a wrist where one motor turns two joints): motor angles
// theta = R q, and drive k acts on motor k:
//   tau = (rigid-body torque) + R^T (J_a R q'' + b R q' + tau_c sgn(R q') + tau_0),
// the products element-wise per motor (docs/models.md#coupled-drives).
#pragma once

#include <array>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace driveid {

/// x_parent = rotation x_child + translation.
struct RigidTransform {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
};
RigidTransform Compose(const RigidTransform& a, const RigidTransform& b);  ///< a then b: x_a = a (b x)
/// Rotation of URDF's rpy: R = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Matrix3d RotationFromRpy(double roll, double pitch, double yaw);

enum class SerialJointType { kRevolute, kPrismatic };

inline constexpr std::size_t kInertialParameters = 10;
using InertialParameters = std::array<double, kInertialParameters>;
/// Names of the 10 parameters in the order above: m, mx, my, mz, Ixx, Ixy, Ixz, Iyy, Iyz, Izz.
const std::array<const char*, kInertialParameters>& InertialParameterNames();

/// From a mass, its centre c and its inertia I_c about c (both in the body
/// frame) to the standard parameters.
InertialParameters InertialFromCentre(double mass, const Eigen::Vector3d& centre, const Eigen::Matrix3d& inertia_at_centre);
/// The parameters of a body moved into another frame (x_new = t x_old).
InertialParameters TransformInertial(const InertialParameters& pi, const RigidTransform& t);
/// The rotational inertia about the frame's origin as a matrix.
Eigen::Matrix3d InertiaMatrix(const InertialParameters& pi);

struct SerialJoint {
  std::string name;
  SerialJointType type = SerialJointType::kRevolute;
  int parent = -1;  ///< index of the parent joint's body; -1: the fixed base
  RigidTransform origin;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double lower = -std::numeric_limits<double>::infinity(), upper = std::numeric_limits<double>::infinity();
  double velocity_limit = std::numeric_limits<double>::infinity();  ///< [rad/s or m/s]
  double effort_limit = std::numeric_limits<double>::infinity();    ///< [N m or N]
  std::string body;  ///< name of the link it moves (the first, if links were merged)
  std::vector<std::string> carried;  ///< the links merged into its body through fixed joints
  /// Its drive's viscous friction per direction (the d |q'| term above;
  /// with a coupling, motor i's: d |(R q')_i|).
  bool viscous_per_direction = false;
  /// A mimic joint (URDF <mimic>): q = mimic_multiplier q_leader +
  /// mimic_offset, `mimic` the leader's index (a joint that mimics none);
  /// -1: a coordinate of its own (docs/models.md#mimic-joints).
  int mimic = -1;
  double mimic_multiplier = 1.0, mimic_offset = 0.0;
};

struct SerialRobot {
  std::string name;
  std::vector<SerialJoint> joints;              ///< movable joints, each after its parent
  std::vector<InertialParameters> bodies;       ///< per joint: the body it moves, in its frame
  Eigen::Vector3d gravity = Eigen::Vector3d(0.0, 0.0, -9.81);  ///< in the base frame [m/s^2]
  /// Motor angles = coupling q (n x n, invertible; empty: each joint its own
  /// motor, the drive referred to the joint). With it, drive i is motor
  /// i's, referred to its own angle (docs/models.md#coupled-drives).
  Eigen::MatrixXd coupling;
  std::size_t size() const { return joints.size(); }
};

/// Per joint drive parameters (the equation above).
struct SerialDriveParameters {
  double armature = 0.0, viscous = 0.0, coulomb = 0.0, offset = 0.0;
  double viscous_asymmetry = 0.0;  ///< d: b+ = viscous + d, b- = viscous - d [N m s/rad or N s/m]
};

}  // namespace driveid
