#include "sim/mujoco_axis_simulator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"
#include "system/child_process.h"
#include "sim/mjcf_files.h"

#include "sim/mujoco_child.h"

namespace driveid {

bool MujocoAxisOptions::IsValid(std::string* error) const {
  return OptionCheck(error)
      .Require(!joint.empty(), "‹joint›: the MJCF joint's name may not be empty")
      .Require(Positive(max_step), "‹mujoco_step›", max_step, "MuJoCo's largest step > 0 s");
}

#if defined(DRIVEID_HAVE_MUJOCO)
namespace {

using namespace mujoco_child;

// Runs in the child: loads, simulates, replies, never returns.
[[noreturn]] void SimulateInChild(const std::string& path, const MujocoRun& run, const std::vector<double>& time,
                                  const std::vector<double>& effort) {
  const Api api = LoadApi();
  mjModel* m = LoadModel(api, path);
  const int drive = FindJoint(api, m, run.drive);
  const int actuator = JointActuator(m, drive, run.drive);
  const double gear = m->actuator_gear[6 * actuator];
  if (!(gear != 0.0) || !std::isfinite(gear)) ReplyError(fmt::format("actuator of '{}' has gear {}", run.drive, gear));
  mjData* d = api.make_data(m);
  if (d == nullptr) ReplyError("MuJoCo cannot allocate its data for this model");
  std::vector<int> qadr, vadr;
  std::vector<double> scale;
  for (const MujocoJointStart& start : run.record) {
    const int joint = FindJoint(api, m, start.joint);
    qadr.push_back(m->jnt_qposadr[joint]);
    vadr.push_back(m->jnt_dofadr[joint]);
    scale.push_back(start.per_gear ? gear : 1.0);
    d->qpos[qadr.back()] = start.position / scale.back();
    d->qvel[vadr.back()] = start.rate / scale.back();
  }
  api.forward(m, d);
  const std::size_t n = time.size(), joints = run.record.size();
  // What this model costs: the first steps timed, the whole run projected.
  double total_steps = 0.0;
  for (std::size_t k = 0; k + 1 < n; ++k) total_steps += std::ceil((time[k + 1] - time[k]) / run.max_step);
  const auto started = std::chrono::steady_clock::now();
  double taken = 0.0;
  bool projected = false;
  std::vector<double> out(2 * n * joints);
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t j = 0; j < joints; ++j) {
      out[2 * n * j + k] = scale[j] * d->qpos[qadr[j]];
      out[2 * n * j + n + k] = scale[j] * d->qvel[vadr[j]];
    }
    if (k + 1 == n) break;
    const double interval = time[k + 1] - time[k];
    const double steps = std::ceil(interval / run.max_step);
    m->opt.timestep = interval / steps;
    d->ctrl[actuator] = effort[k];
    for (double s = 0; s < steps; ++s) {
      api.step(m, d);
      taken += 1.0;
      if (!projected) {
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
        if (seconds < 0.5 && taken < total_steps) continue;
        projected = true;
        const double whole = seconds / taken * total_steps;
        if (whole > run.max_seconds) {
          ReplyError(fmt::format("this model would take about {:.3g} s in MuJoCo ({:.3g} steps at {:.3g} us each, timed "
                                 "over the first {:.0f}), more than {:g} s: a larger ‹mujoco_step›, a shorter log, or a "
                                 "lighter model",
                                 whole, total_steps, 1e6 * seconds / taken, taken, run.max_seconds));
        }
      }
    }
    bool finite = true;
    for (std::size_t j = 0; j < joints; ++j) finite = finite && std::isfinite(d->qpos[qadr[j]]) && std::isfinite(d->qvel[vadr[j]]);
    const char* first_warning = FirstWarning();
    if (first_warning[0] != '\0' || d->warning[mjWARN_BADQACC].number > 0 || !finite) {
      ReplyError(fmt::format("unstable: MuJoCo warned before t = {} s ({}): a smaller MuJoCo step, or an effort "
                             "or parameters that are not physical",
                             time[k + 1], first_warning[0] != '\0' ? first_warning : "a bad acceleration"));
    }
  }
  std::string payload(reinterpret_cast<const char*>(&gear), sizeof gear);
  payload.append(reinterpret_cast<const char*>(out.data()), out.size() * sizeof(double));
  ReplyResult(VersionText(api), payload);
}

}  // namespace

bool MujocoAvailable(std::string*) { return true; }

MujocoRunResponse SimulateMujoco(const std::string& path, const MujocoRun& run, const std::vector<double>& time,
                                 const std::vector<double>& effort) {
  if (!(run.max_step > 0.0) || !std::isfinite(run.max_step)) {
    throw OptionError(fmt::format("MuJoCo's largest step must be a finite number > 0, not {}", run.max_step));
  }
  const std::size_t n = time.size(), joints = run.record.size();
  if (n == 0 || effort.size() != n) throw InputError(fmt::format("{}: no samples to simulate", path));
  CheckMjcfFiles(path);  // before MuJoCo opens anything
  double steps = 0.0;
  for (std::size_t k = 0; k + 1 < n; ++k) steps += std::ceil((time[k + 1] - time[k]) / run.max_step);
  if (steps > 1e9) {
    throw OptionError(fmt::format("{}: {:.3g} MuJoCo steps (the log's length / the largest step): at most 1e9",
                                  path, steps));
  }
  ChildLimits limits;
  // About a microsecond per step of a one-joint model; a generous margin.
  // The child refuses a run its first steps project beyond max_seconds; this is the backstop.
  limits.seconds = static_cast<long>(std::min(3600.0, run.max_seconds + 30.0));
  limits.address_space_bytes = 4.0 * (1 << 30) + 32.0 * static_cast<double>(n * std::max<std::size_t>(joints, 1));
  const std::size_t payload = 2 * n * joints * sizeof(double) + sizeof(double);
  const std::string where = fmt::format("{} (joint '{}')", path, run.drive);
  MujocoRunResponse response;
  const std::string reply = RunMujocoChild([&] { SimulateInChild(path, run, time, effort); }, limits, where, payload,
                                           &response.library);
  const char* data = reply.data();
  std::memcpy(&response.gear, data, sizeof(double));
  data += sizeof(double);
  for (std::size_t j = 0; j < joints; ++j) {
    std::vector<double> q(n), v(n);
    std::memcpy(q.data(), data + (2 * j) * n * sizeof(double), n * sizeof(double));
    std::memcpy(v.data(), data + (2 * j + 1) * n * sizeof(double), n * sizeof(double));
    response.position.push_back(std::move(q));
    response.rate.push_back(std::move(v));
  }
  return response;
}

MujocoAxisResponse SimulateMujocoAxis(const std::string& path, const MujocoAxisOptions& options,
                                      const std::vector<double>& time, const std::vector<double>& effort, double q0,
                                      double v0) {
  RequireValid(options);
  MujocoRun run;
  run.drive = options.joint;
  run.record = {{options.joint, q0, v0, false}};
  run.max_step = options.max_step;
  MujocoRunResponse full = SimulateMujoco(path, run, time, effort);
  MujocoAxisResponse response;
  response.position = std::move(full.position.front());
  response.rate = std::move(full.rate.front());
  response.library = std::move(full.library);
  return response;
}

#else  // no MuJoCo in this build

bool MujocoAvailable(std::string* why) {
  if (why) *why = "this build has no MuJoCo (libmujoco-dev was not found when it was built): install it and rebuild";
  return false;
}

MujocoRunResponse SimulateMujoco(const std::string& path, const MujocoRun&, const std::vector<double>&,
                                 const std::vector<double>&) {
  std::string why;
  MujocoAvailable(&why);
  throw InputError(fmt::format("{}: {} (scripts/setup installs it where Debian has it)", path, why));
}

MujocoAxisResponse SimulateMujocoAxis(const std::string& path, const MujocoAxisOptions&, const std::vector<double>& time,
                                      const std::vector<double>& effort, double, double) {
  SimulateMujoco(path, MujocoRun{}, time, effort);
  return {};
}

#endif

}  // namespace driveid
