// A term of a serial arm's drive (models/serial_robot.h,
// docs/models.md#serial-robot) as an object, as the axis's
// (models/axis_term.h) and the elastic joint's (models/joint_term.h) are.
// Each term is one parameter p_k of every joint's drive and its column of
// the regressor: the torque per unit of p_k at the drive's motion,
//   tau_drive = sum_k p_k phi_k(a, v),
// with a [rad/s^2 or m/s^2] and v [rad/s or m/s] the drive's acceleration
// and rate: the joint's own, or with a coupling R its motor's, (R q'')_i and
// (R q')_i, whose torque reaches the joints as R_i^T
// (docs/models.md#coupled-drives). From these columns the tools build the
// regressor's drive columns (models/serial_dynamics.cc), their names, the
// parameter file's drive keys (params/serial_robot_section.cc) and the
// consistent fit's drive block and bounds (fit/robot/consistent_parameters.cc).
// The list is DRIVEID_SERIAL_DRIVE_TERMS in lib/CMakeLists.txt; a new term is
// one file of models/serial_drive_terms/, its name there, a member of
// SerialDriveParameters, and kSerialDriveTerms raised
// (docs/adding-a-model.md).
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

namespace driveid {

struct SerialDriveParameters;
struct SerialJoint;

/// The registered terms' count: the columns of a drive in the regressor.
inline constexpr std::size_t kSerialDriveTerms = 5;

class SerialDriveTerm {
 public:
  virtual ~SerialDriveTerm() = default;
  /// Its key in the parameter file's drives and the prefix of its regressor
  /// column's name ("armature" -> armature_<joint>).
  virtual const char* key() const = 0;
  /// Its value in SerialDriveParameters.
  virtual double SerialDriveParameters::*member() const = 0;
  /// Physically >= 0 (an inertia, a dissipation): the consistent fit bounds it.
  virtual bool nonnegative() const = 0;
  /// Part of every joint's model (false: only where the joint asks for it,
  /// Asked; its column is zero elsewhere, it is then no parameter of the
  /// model, and the parameter file writes it only where asked).
  virtual bool always() const { return true; }
  /// Whether joint `joint` asks for it (always() terms: every joint).
  virtual bool Asked(const SerialJoint&) const { return true; }
  /// Makes `joint` ask for it (nothing for always() terms).
  virtual void Ask(SerialJoint&) const {}
  /// phi(a, v): the torque per unit of the parameter.
  virtual double Column(double acceleration, double rate) const = 0;
};

/// The registered terms in the regressor's order (models/serial_drive_terms.cc).
const std::vector<const SerialDriveTerm*>& SerialDriveTerms();

#define DRIVEID_SERIAL_DRIVE_TERM(name, Class) \
  std::unique_ptr<SerialDriveTerm> MakeSerialDriveTerm_##name() { return std::make_unique<Class>(); }

}  // namespace driveid
