// A fitted axis' parameters written where controllers and simulators read
// them (docs/export.md): MuJoCo's MJCF, URDF, WPILib's Java feed-forward
// classes, a C header for firmware, and JSON. Each target holds what it can
// represent; what it cannot is said in the written file's comments and in
// docs/export.md, never dropped silently.
//
// From the axis model (models/axis.h, docs/models.md#axis)
//   tau = J q'' + b q' + tau_c sgn q' + tau_0 + g_c cos q + g_s sin q:
//   MJCF   hinge (slide when linear) joint: armature + body inertia = J,
//          damping = b, frictionloss = tau_c (MuJoCo's friction is a soft
//          constraint, not a sticking Coulomb law: docs/export.md), an
//          actuator force = ctrl - tau_0 (affine bias), gravity as a point
//          mass m at distance r with m g r = Kg, placed at angle Kg_angle;
//   URDF   <dynamics damping="b" friction="tau_c"/>, the link's inertia J;
//   WPILib (Java and C++, export/wpilib_export.h) SimpleMotorFeedforward(ks, kv, ka), ArmFeedforward(ks, kg, kv, ka)
//          when gravity was fitted, ElevatorFeedforward(ks, kg, kv, ka) for a
//          linear axis (kg = the offset); per direction where fitted;
//   C header and JSON: the feed-forward gains with units and std.
#pragma once

#include <string>

#include "export/export_target.h"
#include "export/export_text.h"
#include "params/parameter_file.h"

namespace driveid {

/// The target a name spells (export/export_target.h); InputError listing the names for any other.
ExportTarget ParseExportTarget(const std::string& name);

/// The text of `target` for the file's axis section and feed-forward
/// section, or for its elastic joint (export/joint_export.h). Throws
/// InputError when the file has neither (the drive train, robot and C-drive
/// have no export target yet).
std::string ExportParameters(const ParameterFile& file, ExportTarget target, const ExportOptions& options);

}  // namespace driveid
