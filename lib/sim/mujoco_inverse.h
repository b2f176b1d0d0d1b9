// A robot's MJCF (docs/export.md#validation-in-mujoco; `export --to mjcf` of
// a serial robot, or any MuJoCo model whose joints each have one actuator)
// asked, by MuJoCo's inverse dynamics (mj_inverse), for the actuator
// controls that produce logged motions: at each sample the named joints'
// qpos, qvel and qacc are set (the model's other joints at qpos0, at rest),
// and each joint's generalised force f = qfrc_inverse (mass matrix with
// armature, bias forces, damping, friction loss and limits as MuJoCo models
// them) becomes the control its actuator needs:
//   f = gear (gain ctrl + b0 + b1 length + b2 velocity)  =>  ctrl.
// Runs in a child process as sim/mujoco_axis_simulator.h does.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace driveid {

/// The model's hinge and slide joints in its order. InputError naming the
/// file when MuJoCo is not in this build or refuses it.
std::vector<std::string> MujocoJointNames(const std::string& path);

struct MujocoInverseResponse {
  std::vector<std::vector<double>> control;  ///< [joint][sample]: the actuator's ctrl
  std::string library;                       ///< MuJoCo's version
};

/// Per sample k: q[k], qd[k], qdd[k] over `joints` (in that order). Throws
/// InputError naming the file and joint (no such joint, not exactly one
/// joint actuator with a fixed gain and no or an affine bias, a nonfinite
/// result).
MujocoInverseResponse MujocoInverseDynamics(const std::string& path, const std::vector<std::string>& joints,
                                            const std::vector<Eigen::VectorXd>& q,
                                            const std::vector<Eigen::VectorXd>& qd,
                                            const std::vector<Eigen::VectorXd>& qdd);

}  // namespace driveid
