// The reference arm (tests/support/reference_serial_arm.h) written as a URDF
// by hand (no library code): a revolute joint per arm joint with its
// inertial, and with `extras` a tool link fixed to the last body (its mass
// merged into that body by a reader), a visual mesh and a transmission —
// what a user's URDF carries and an export must keep.
#pragma once

#include <string>

#include "support/reference_serial_arm.h"

namespace reference {

std::string ArmUrdf(const Arm& arm, bool extras = false);

/// The tool's mass [kg], centre (in its link frame, which sits 0.1 m along
/// x of the last body's frame) and inertia (diagonal, about the centre).
inline constexpr double kToolMass = 0.5, kToolCentreX = 0.02, kToolInertia = 1e-3, kToolOffsetX = 0.1;

}  // namespace reference
