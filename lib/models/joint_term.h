// A term of the elastic joint (models/joint.h, docs/models.md#elastic-joint)
// as an object, as the axis's terms are (models/axis_term.h): it owns its
// parameters' table rows and the torque each of them takes, per unit of the
// parameter, from the motor mass and from the link mass, and what a
// shaft-torque sensor in the elastic element reads of it. From these columns
// the registry (models/joint_terms.cc) builds everything the tools use:
//   - the identification's three equations (fit/joint/joint_fit.h):
//       motor:  tau_m    = sum_i p_i phi_i^motor
//       total:  tau_m    = sum_i p_i (phi_i^motor + phi_i^link)
//       sensor: tau_link = sum_i p_i phi_i^sensor
//     (the link has no actuator: sum_i p_i phi_i^link = 0 is its equation);
//   - for the terms linear in the motion, the matrices of
//       M x'' + D x' + K x = (tau_m, 0),  x = (theta_m, theta_l),
//     read off the columns at unit motions, which give the frequency
//     response (Z(s) = M s^2 + D s + K) and the sampled state space.
// Conventions (link side): theta_m = q_motor / n, tau_m = n tau, angles
// [rad], rates [rad/s], accelerations [rad/s^2], torques [N m]. A dry
// friction column is sgn of its mass's rate.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "models/parameter_table.h"

namespace driveid {

struct JointParameters;
struct JointSection;
using JointRow = ParameterRow<JointSection, JointParameters>;

/// Motion of the two masses at one instant (link side).
struct JointMotion {
  double motor_angle = 0.0, motor_rate = 0.0, motor_acceleration = 0.0;
  double link_angle = 0.0, link_rate = 0.0, link_acceleration = 0.0;
};

/// One parameter's column: the torque per unit of the parameter it takes
/// from the motor mass and from the link mass, and its part of a shaft
/// torque sensor's reading [N m per unit].
struct JointColumn {
  double motor = 0.0, link = 0.0, sensor = 0.0;
};

/// How a parameter's torque depends on the motion.
enum class JointRowKind {
  kLinear,    ///< linear in the angles, rates and accelerations (in M, D, K)
  kDry,       ///< p sgn(rate) of one mass (Coulomb)
  kConstant,  ///< independent of the motion (an offset)
  kAngle,     ///< nonlinear in the link angle (gravity)
  kSensor,    ///< only in the sensor's reading (its bias)
};

class JointModelTerm {
 public:
  virtual ~JointModelTerm() = default;
  /// What messages call it ("the spring").
  virtual std::string name() const = 0;
  /// Its parameters' rows; each points to its member of JointParameters.
  virtual std::vector<JointRow> Rows() const = 0;
  virtual JointRowKind Kind(std::size_t row) const = 0;
  /// The columns of its rows at the motion x, into out[0 .. rows).
  virtual void Columns(const JointMotion& x, JointColumn* out) const = 0;
};

/// The registered terms, in the parameter file's order (models/joint_terms.cc).
const std::vector<const JointModelTerm*>& JointTerms();

/// The term of parameter j (JointParameterTable order) and its row there.
struct JointTermParameter {
  const JointModelTerm* term = nullptr;
  std::size_t row = 0;
};
const JointTermParameter& JointParameterTerm(std::size_t j);

/// The linear terms' matrices at the values p, rows and columns (motor,
/// link): M [kg m^2], D [N m s/rad], K [N m/rad].
struct JointLinearDynamics {
  std::array<std::array<double, 2>, 2> mass{}, damping{}, stiffness{};
};
JointLinearDynamics CalcJointLinearDynamics(const JointParameters& p);
/// The same for parameter j at 1 and every other at 0 (its partial);
/// zero matrices for a parameter that is not kLinear.
JointLinearDynamics JointLinearPartial(std::size_t j);
/// The kLinear parameters, in table order.
const std::vector<std::size_t>& JointLinearParameters();

#define DRIVEID_JOINT_TERM(name, Class) \
  std::unique_ptr<JointModelTerm> MakeJointTerm_##name() { return std::make_unique<Class>(); }

}  // namespace driveid
