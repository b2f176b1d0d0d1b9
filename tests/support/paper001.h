// The C-drive of seed 001 for tests: lead 60 mm, Table I dissipation, and
// the inertias the issue states (I_h 6e-4, I_c 1.6e-3 kg m^2, m 2 kg).
#pragma once

#include "models/cdrive.h"

namespace testing_support {

inline driveid::CDriveParameters TableOneCDrive() {
  driveid::CDriveParameters p;
  p.lead = 0.06;
  p.hub_inertia = 6e-4;
  p.collar_inertia = 1.6e-3;
  p.collar_mass = 2.0;
  p.viscous_motor = 0.002655;
  p.viscous_collar = 0.004333;
  p.coulomb_motor = 0.1086;
  p.coulomb_collar = 0.1501;
  return p;
}

}  // namespace testing_support
