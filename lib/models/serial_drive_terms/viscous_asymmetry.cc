// Viscous friction per direction, where the joint asks for it
// (SerialJoint::viscous_per_direction): the asymmetry d [N m s/rad or N s/m]
// of b+ = viscous + d, b- = viscous - d, whose torque is d |v|. Elsewhere it
// is no parameter of the model and its column is zero.
#include <cmath>
#include <memory>

#include "models/serial_drive_term.h"
#include "models/serial_robot.h"

namespace driveid {
namespace {

class SerialViscousAsymmetryTerm final : public SerialDriveTerm {
 public:
  const char* key() const override { return "viscous_asymmetry"; }
  double SerialDriveParameters::*member() const override { return &SerialDriveParameters::viscous_asymmetry; }
  bool nonnegative() const override { return false; }
  bool always() const override { return false; }
  bool Asked(const SerialJoint& joint) const override { return joint.viscous_per_direction; }
  void Ask(SerialJoint& joint) const override { joint.viscous_per_direction = true; }
  double Column(double, double rate) const override { return std::abs(rate); }
};

}  // namespace

DRIVEID_SERIAL_DRIVE_TERM(viscous_asymmetry, SerialViscousAsymmetryTerm)

}  // namespace driveid
