// Viscous friction of the drive, b [N m s/rad or N s/m]: b v.
#include <memory>

#include "models/serial_drive_term.h"
#include "models/serial_robot.h"

namespace driveid {
namespace {

class SerialViscousTerm final : public SerialDriveTerm {
 public:
  const char* key() const override { return "viscous"; }
  double SerialDriveParameters::*member() const override { return &SerialDriveParameters::viscous; }
  bool nonnegative() const override { return true; }
  double Column(double, double rate) const override { return rate; }
};

}  // namespace

DRIVEID_SERIAL_DRIVE_TERM(viscous, SerialViscousTerm)

}  // namespace driveid
