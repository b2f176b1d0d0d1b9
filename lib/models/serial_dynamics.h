// Inverse dynamics of a serial robot (models/serial_robot.h,
// docs/models.md#serial-robot) by the recursive Newton-Euler algorithm
// (Luh, Walker and Paul 1980), and its regressor: the same recursion run on
// the 10 inertial parameters of each body as unknowns, which the torques are
// linear in (Atkeson, An and Hollerbach 1986).
//
// Outward pass, body i with parent p, R and r its frame's orientation and
// origin in p's frame at q_i, s its axis; gravity enters as an upward
// acceleration of the base (a_0 = -g):
//   w_i  = R^T w_p + s q_i'                       (revolute)
//   w_i' = R^T w_p' + s q_i'' + (R^T w_p) x s q_i'
//   a_i  = R^T (a_p + w_p' x r + w_p x (w_p x r))  (+ 2 w_i x s q_i' + s q_i'' prismatic)
// The wrench body i needs at its origin, linear in (m, h, I):
//   f_i = m a_i + w_i' x h + w_i x (w_i x h)
//   n_i = I w_i' + w_i x (I w_i) + h x a_i
// Inward pass: a joint carries its body's wrench and its children's,
// moved to its frame (f_p += R f_c, n_p += R n_c + r x R f_c), and its
// torque is s . n (revolute) or its force s . f (prismatic).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "models/serial_drive_term.h"
#include "models/serial_robot.h"

namespace driveid {

/// Rigid-body joint torques [N m or N] at q, q', q'' (each robot.size()),
/// with the bodies' parameters `bodies` (robot.bodies when omitted).
Eigen::VectorXd CalcSerialRigidTorque(const SerialRobot& robot, const std::vector<InertialParameters>& bodies,
                                      const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd);

/// Columns per joint of the full regressor: its body's 10 inertial
/// parameters, then its drive's terms (models/serial_drive_term.h: armature,
/// viscous, Coulomb, offset and viscous asymmetry, the last |q'| where the
/// joint asks for viscous friction per direction, else zero: never reaching
/// a torque).
inline constexpr std::size_t kSerialColumnsPerJoint = kInertialParameters + kSerialDriveTerms;
/// The column of drive term k (SerialDriveTerms() order) within a joint's.
inline constexpr std::size_t SerialDriveColumn(std::size_t k) { return kInertialParameters + k; }

/// The regressor Y (n x 15 n) with tau = Y theta, theta stacked joint by
/// joint as above. `y` must be n x 15 n; it is overwritten. With a coupling
/// R (SerialRobot::coupling, motor angles theta_m = R q), drive i is motor
/// i's: its columns are R_i^T times (R q'')_i, (R q')_i, sgn (R q')_i, 1
/// and |R q'|_i (docs/models.md#coupled-drives).
void CalcSerialRegressor(const SerialRobot& robot, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                         const Eigen::VectorXd& qdd, Eigen::Ref<Eigen::MatrixXd> y);

/// The robot's coordinates: the joints that mimic none (indices, in order).
/// A robot without mimic joints has every joint a coordinate.
std::vector<std::size_t> SerialCoordinates(const SerialRobot& robot);
/// Their joints' names: a log's torque channels.
std::vector<std::string> SerialCoordinateNames(const SerialRobot& robot);
/// Every joint's q, q', q'' (robot.size()) from the coordinates' (each
/// SerialCoordinates(robot).size()): q = G q_c + o, q' = G q_c', q'' = G q_c''.
void ExpandSerialMotion(const SerialRobot& robot, const Eigen::VectorXd& q_c, const Eigen::VectorXd& qd_c,
                        const Eigen::VectorXd& qdd_c, Eigen::VectorXd& q, Eigen::VectorXd& qd, Eigen::VectorXd& qdd);
/// The regressor in the coordinates, G^T Y at the expanded motion (virtual
/// work: a mimic joint's torque reaches its leader times its multiplier),
/// m x 15 n for m coordinates (`y` that size; overwritten). Without mimic
/// joints it is CalcSerialRegressor.
void CalcSerialCoordinateRegressor(const SerialRobot& robot, const Eigen::VectorXd& q_c, const Eigen::VectorXd& qd_c,
                                   const Eigen::VectorXd& qdd_c, Eigen::Ref<Eigen::MatrixXd> y);

/// The n x n coupling R: the identity but for `block` (k x k) on the rows and
/// columns `coupled` (joint indices).
Eigen::MatrixXd SerialCouplingMatrix(std::size_t joints, const std::vector<std::size_t>& coupled,
                                     const Eigen::MatrixXd& block);

/// The names of the regressor's columns: m_<body> .. Izz_<body>, then each
/// drive term's <key>_<joint> (armature_<joint> .. viscous_asymmetry_<joint>).
std::vector<std::string> SerialParameterNames(const SerialRobot& robot);
/// theta of the robot's own inertials and the given drives (zero drives when empty).
Eigen::VectorXd SerialParameterVector(const SerialRobot& robot, const std::vector<SerialDriveParameters>& drives);

/// The frame of every body in the base frame at q (forward kinematics).
std::vector<RigidTransform> SerialBodyPoses(const SerialRobot& robot, const Eigen::VectorXd& q);
/// The transform of joint i's body in its parent's frame at q_i.
RigidTransform SerialJointTransform(const SerialJoint& joint, double q);

}  // namespace driveid
