// A constant torque of the drive, tau_0 [N m or N]: its current sensor's offset or a
// constant load. It separates from the Coulomb friction only with motion in both directions.
#include <memory>

#include "models/serial_drive_term.h"
#include "models/serial_robot.h"

namespace driveid {
namespace {

class SerialOffsetTerm final : public SerialDriveTerm {
 public:
  const char* key() const override { return "offset"; }
  double SerialDriveParameters::*member() const override { return &SerialDriveParameters::offset; }
  bool nonnegative() const override { return false; }
  double Column(double, double) const override { return 1.0; }
};

}  // namespace

DRIVEID_SERIAL_DRIVE_TERM(offset, SerialOffsetTerm)

}  // namespace driveid
