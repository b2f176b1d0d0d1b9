#include "sim/mujoco_inverse.h"

#include <cmath>
#include <cstring>

#include <fmt/format.h>

#include "core/errors.h"
#include "system/child_process.h"
#include "sim/mjcf_files.h"
#include "sim/mujoco_axis_simulator.h"
#include "sim/mujoco_child.h"

namespace driveid {

#if defined(DRIVEID_HAVE_MUJOCO)
namespace {

using namespace mujoco_child;

constexpr std::size_t kMaxJoints = 1000;

[[noreturn]] void NamesInChild(const std::string& path) {
  const Api api = LoadApi();
  const mjModel* m = LoadModel(api, path);
  std::string payload;
  for (int j = 0; j < m->njnt; ++j) {
    if (m->jnt_type[j] != mjJNT_HINGE && m->jnt_type[j] != mjJNT_SLIDE) continue;
    const char* name = api.id2name(m, mjOBJ_JOINT, j);
    payload += name ? name : "";
    payload += '\0';
  }
  ReplyResult(VersionText(api), payload);
}

// The control an actuator needs for the force f on its joint.
struct Actuation {
  int qpos = 0, dof = 0, actuator = 0;
  double gear = 1.0;
};

Actuation Actuated(const Api& api, const mjModel* m, const std::string& name) {
  Actuation a;
  const int joint = FindJoint(api, m, name);
  a.qpos = m->jnt_qposadr[joint];
  a.dof = m->jnt_dofadr[joint];
  a.actuator = JointActuator(m, joint, name);
  a.gear = m->actuator_gear[6 * a.actuator];
  const double gain = m->actuator_gainprm[mjNGAIN * a.actuator];
  if (m->actuator_gaintype[a.actuator] != mjGAIN_FIXED || !(gain != 0.0) || !std::isfinite(gain) ||
      !(a.gear != 0.0) || !std::isfinite(a.gear) ||
      (m->actuator_biastype[a.actuator] != mjBIAS_NONE && m->actuator_biastype[a.actuator] != mjBIAS_AFFINE) ||
      m->actuator_dyntype[a.actuator] != mjDYN_NONE) {
    ReplyError(fmt::format("joint '{}': its actuator needs a fixed nonzero gain and gear, no activation dynamics and "
                           "no or an affine bias for its control to follow from a force",
                           name));
  }
  return a;
}

[[noreturn]] void InverseInChild(const std::string& path, const std::vector<std::string>& joints,
                                 const std::vector<Eigen::VectorXd>& q, const std::vector<Eigen::VectorXd>& qd,
                                 const std::vector<Eigen::VectorXd>& qdd) {
  const Api api = LoadApi();
  mjModel* m = LoadModel(api, path);
  std::vector<Actuation> act;
  for (const std::string& name : joints) act.push_back(Actuated(api, m, name));
  mjData* d = api.make_data(m);
  if (d == nullptr) ReplyError("MuJoCo cannot allocate its data for this model");
  const std::size_t n = q.size(), count = joints.size();
  std::vector<double> out(n * count);
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t j = 0; j < count; ++j) {
      const auto i = static_cast<Eigen::Index>(j);
      d->qpos[act[j].qpos] = q[k](i);
      d->qvel[act[j].dof] = qd[k](i);
      d->qacc[act[j].dof] = qdd[k](i);
    }
    api.inverse(m, d);
    for (std::size_t j = 0; j < count; ++j) {
      const int a = act[j].actuator;
      const double* bias = m->actuator_biasprm + mjNBIAS * a;
      const double affine = m->actuator_biastype[a] == mjBIAS_AFFINE
                                ? bias[0] + bias[1] * d->actuator_length[a] + bias[2] * d->actuator_velocity[a]
                                : 0.0;
      const double control = (d->qfrc_inverse[act[j].dof] / act[j].gear - affine) / m->actuator_gainprm[mjNGAIN * a];
      if (!std::isfinite(control)) ReplyError(fmt::format("joint '{}': a nonfinite force at sample {}", joints[j], k));
      out[j * n + k] = control;
    }
  }
  ReplyResult(VersionText(api), std::string(reinterpret_cast<const char*>(out.data()), out.size() * sizeof(double)));
}

}  // namespace

std::vector<std::string> MujocoJointNames(const std::string& path) {
  CheckMjcfFiles(path);
  ChildLimits limits;
  limits.seconds = 60;
  limits.address_space_bytes = 4.0 * (1 << 30);
  // The names' bytes are not known in advance: at most kMaxJoints of 256.
  std::string version;
  const std::string list = RunMujocoChild([&] { NamesInChild(path); }, limits, path, kMaxJoints * 257, &version, false);
  std::vector<std::string> out;
  for (std::size_t at = 0; at < list.size();) {
    const std::size_t end = list.find('\0', at);
    if (end == std::string::npos) break;
    out.push_back(list.substr(at, end - at));
    at = end + 1;
  }
  if (out.empty()) throw InputError(fmt::format("{}: the model has no hinge or slide joint", path));
  return out;
}

MujocoInverseResponse MujocoInverseDynamics(const std::string& path, const std::vector<std::string>& joints,
                                            const std::vector<Eigen::VectorXd>& q,
                                            const std::vector<Eigen::VectorXd>& qd,
                                            const std::vector<Eigen::VectorXd>& qdd) {
  const std::size_t n = q.size(), count = joints.size();
  if (n == 0 || qd.size() != n || qdd.size() != n) throw InputError(fmt::format("{}: no samples to predict", path));
  for (std::size_t k = 0; k < n; ++k) {
    if (static_cast<std::size_t>(q[k].size()) != count || static_cast<std::size_t>(qd[k].size()) != count ||
        static_cast<std::size_t>(qdd[k].size()) != count) {
      throw std::logic_error("MujocoInverseDynamics: one value per joint");
    }
  }
  CheckMjcfFiles(path);
  ChildLimits limits;
  limits.seconds = 600;
  limits.address_space_bytes = 4.0 * (1 << 30) + 8.0 * static_cast<double>(n * count);
  MujocoInverseResponse response;
  const std::string reply = RunMujocoChild([&] { InverseInChild(path, joints, q, qd, qdd); }, limits, path,
                                           n * count * sizeof(double), &response.library);
  for (std::size_t j = 0; j < count; ++j) {
    std::vector<double> control(n);
    std::memcpy(control.data(), reply.data() + j * n * sizeof(double), n * sizeof(double));
    response.control.push_back(std::move(control));
  }
  return response;
}

#else  // no MuJoCo in this build

std::vector<std::string> MujocoJointNames(const std::string& path) {
  std::string why;
  MujocoAvailable(&why);
  throw InputError(fmt::format("{}: {} (scripts/setup installs it where Debian has it)", path, why));
}

MujocoInverseResponse MujocoInverseDynamics(const std::string& path, const std::vector<std::string>&,
                                            const std::vector<Eigen::VectorXd>&, const std::vector<Eigen::VectorXd>&,
                                            const std::vector<Eigen::VectorXd>&) {
  MujocoJointNames(path);
  return {};
}

#endif

}  // namespace driveid
