// The elastic joint (models/joint.h, docs/models.md#elastic-joint) where
// simulators and firmware read it (docs/export.md#elastic-joint):
//   MJCF   two hinge joints on the link side, the motor (armature J_m,
//          damping b_m, frictionloss c_m, driven through gear n with the
//          offset as affine bias: n tau - tau_0) and the link (J_l, b_l,
//          c_l, gravity as a point mass), coupled by a fixed tendon
//          L = theta_m - theta_l with stiffness k and damping d: the spring
//          k (theta_m - theta_l) + d (theta_m' - theta_l') acts on both, and
//          each friction on its own absolute rate (a child joint's damping
//          would act on the twist rate instead);
//   URDF   the link's joint (b_l, c_l, J_l); what URDF cannot hold (the
//          motor side, the spring) said in comments;
//   C header every value with unit and std.
#pragma once

#include <string>

#include "export/export_target.h"
#include "export/export_text.h"
#include "params/parameter_file.h"

namespace driveid {

/// Throws InputError naming what is missing (gear_ratio, J_m, J_l, k > 0) or
/// a target the joint has none in (wpilib-java, json).
std::string ExportJoint(const JointSection& joint, const ParameterFile& file, ExportTarget target,
                        const ExportOptions& options);

}  // namespace driveid
