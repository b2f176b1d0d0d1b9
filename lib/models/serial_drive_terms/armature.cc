// The rotor's inertia referred to the drive's angle, J_a [kg m^2 or kg]:
// J_a a. It joins its link's inertia about the same axis in a base parameter.
#include <memory>

#include "models/serial_drive_term.h"
#include "models/serial_robot.h"

namespace driveid {
namespace {

class SerialArmatureTerm final : public SerialDriveTerm {
 public:
  const char* key() const override { return "armature"; }
  double SerialDriveParameters::*member() const override { return &SerialDriveParameters::armature; }
  bool nonnegative() const override { return true; }
  double Column(double acceleration, double) const override { return acceleration; }
};

}  // namespace

DRIVEID_SERIAL_DRIVE_TERM(armature, SerialArmatureTerm)

}  // namespace driveid
