// The paper's drive-train values (seed 000 section 4, docs/models.md#drive-train) for tests:
// n_g^2 Theta_motor = 0.413 kg m^2, n_g^2 Theta_g = 0.043 kg m^2.
#pragma once

#include "models/drivetrain.h"

namespace testing_support {

inline driveid::DriveTrainParameters PaperDriveTrain() {
  driveid::DriveTrainParameters p;
  p.gear_ratio = 80.0;
  p.link_stiffness = 15000.0;
  p.gearbox_stiffness = 18375.0;
  p.motor_inertia = 0.413 / 6400.0;
  p.gearbox_inertia = 0.043 / 6400.0;
  p.viscous_friction = 0.016;
  p.coulomb_friction = 5.0;
  return p;
}

}  // namespace testing_support
