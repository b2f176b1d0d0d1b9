// Coulomb friction of the drive, tau_c [N m or N]: tau_c sgn v (zero at
// standstill, where the fit leaves the rows out).
#include <memory>

#include "models/serial_drive_term.h"
#include "models/serial_robot.h"

namespace driveid {
namespace {

class SerialCoulombTerm final : public SerialDriveTerm {
 public:
  const char* key() const override { return "coulomb"; }
  double SerialDriveParameters::*member() const override { return &SerialDriveParameters::coulomb; }
  bool nonnegative() const override { return true; }
  double Column(double, double rate) const override { return static_cast<double>((rate > 0.0) - (rate < 0.0)); }
};

}  // namespace

DRIVEID_SERIAL_DRIVE_TERM(coulomb, SerialCoulombTerm)

}  // namespace driveid
