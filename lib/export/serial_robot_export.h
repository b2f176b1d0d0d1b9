// A serial robot's identified model (docs/models.md#serial-robot) where
// simulators read it (docs/export.md#serial-robot), from the serial_robot
// section's physically consistent bodies and drives:
//   URDF   the fitted-on URDF as the user wrote it (visuals, meshes,
//          transmissions kept), each moving link's <inertial> the body's
//          identified one (mass, centre, inertia about the centre), the
//          <inertial> of links merged into it removed, and per joint
//          <dynamics damping="b" friction="tau_c"/>; the armature J_a and
//          offset tau_0, which URDF cannot hold, in comments;
//   MJCF   the body tree (each body at its joint's origin in its parent's
//          frame), hinge or slide joints with range, armature J_a, damping
//          b, frictionloss tau_c; inertials as identified; one actuator per
//          joint whose control is the logged torque: force = ctrl - tau_0.
#pragma once

#include <string>

#include "export/export_target.h"
#include "export/export_text.h"
#include "params/parameter_file.h"

namespace driveid {

/// Throws InputError when the section has no consistent bodies, the URDF
/// (ExportOptions::urdf, else the section's) is not the fitted one, or the
/// target has no form for a robot (wpilib-java, wpilib-cpp, c-header, json).
std::string ExportSerialRobot(const ParameterFile& file, ExportTarget target, const ExportOptions& options);

}  // namespace driveid
