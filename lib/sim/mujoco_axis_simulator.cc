#include "sim/mujoco_axis_simulator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"
#include "io/child_process.h"
#include "sim/mjcf_files.h"

#if defined(DRIVEID_HAVE_MUJOCO)
#include <dlfcn.h>
#include <unistd.h>

#include <mujoco/mujoco.h>
#endif

namespace driveid {

bool MujocoAxisOptions::IsValid(std::string* error) const {
  return OptionCheck(error)
      .Require(!joint.empty(), "‹joint›: the MJCF joint's name may not be empty")
      .Require(Positive(max_step), "‹mujoco_step›", max_step, "MuJoCo's largest step > 0 s");
}

#if defined(DRIVEID_HAVE_MUJOCO)
namespace {

// The child's reply on its standard output: 'E' and a message, or 'R', the
// version text's length (one byte) and text, then n positions and n rates.
[[noreturn]] void ReplyError(const std::string& message) {
  const std::string reply = "E" + message;
  WriteAll(STDOUT_FILENO, reply.data(), reply.size());
  ::_exit(0);
}

void OnMujocoError(const char* message) { ReplyError(fmt::format("MuJoCo: {}", message)); }

// MuJoCo's first warning (a bad acceleration, a full constraint buffer): it
// resets the simulation and its warning counts, so the message is kept here.
char first_warning[512] = "";
void OnMujocoWarning(const char* message) {
  if (first_warning[0] == '\0') std::snprintf(first_warning, sizeof first_warning, "%s", message);
}

template <typename F>
F Symbol(void* library, const char* name) {
  void* address = ::dlsym(library, name);
  if (address == nullptr) ReplyError(fmt::format("{} has no symbol {}", DRIVEID_MUJOCO_LIBRARY, name));
  return reinterpret_cast<F>(address);
}

struct Api {
  int (*version)();
  mjModel* (*load_xml)(const char*, const mjVFS*, char*, int);
  mjData* (*make_data)(const mjModel*);
  void (*forward)(const mjModel*, mjData*);
  void (*step)(const mjModel*, mjData*);
  int (*name2id)(const mjModel*, int, const char*);
  const char* (*id2name)(const mjModel*, int, int);
};

Api LoadApi() {
  void* library = ::dlopen(DRIVEID_MUJOCO_LIBRARY, RTLD_NOW | RTLD_LOCAL);
  if (library == nullptr) {
    const char* why = ::dlerror();
    ReplyError(fmt::format("cannot load MuJoCo ({}): install Debian's libmujoco-dev (scripts/setup)",
                           why ? why : DRIVEID_MUJOCO_LIBRARY));
  }
  *Symbol<void (**)(const char*)>(library, "mju_user_error") = OnMujocoError;
  *Symbol<void (**)(const char*)>(library, "mju_user_warning") = OnMujocoWarning;
  Api api;
  api.version = Symbol<int (*)()>(library, "mj_version");
  api.load_xml = Symbol<mjModel* (*)(const char*, const mjVFS*, char*, int)>(library, "mj_loadXML");
  api.make_data = Symbol<mjData* (*)(const mjModel*)>(library, "mj_makeData");
  api.forward = Symbol<void (*)(const mjModel*, mjData*)>(library, "mj_forward");
  api.step = Symbol<void (*)(const mjModel*, mjData*)>(library, "mj_step");
  api.name2id = Symbol<int (*)(const mjModel*, int, const char*)>(library, "mj_name2id");
  api.id2name = Symbol<const char* (*)(const mjModel*, int, int)>(library, "mj_id2name");
  if (api.version() != mjVERSION_HEADER) {
    ReplyError(fmt::format("MuJoCo library version {} differs from the header driveid was built with ({}): rebuild",
                           api.version(), mjVERSION_HEADER));
  }
  return api;
}

// The hinge and slide joints' names, for a message.
std::string JointNames(const Api& api, const mjModel* m) {
  std::string out;
  int listed = 0;
  for (int j = 0; j < m->njnt && listed < 10; ++j) {
    if (m->jnt_type[j] != mjJNT_HINGE && m->jnt_type[j] != mjJNT_SLIDE) continue;
    const char* name = api.id2name(m, mjOBJ_JOINT, j);
    out += fmt::format("{}'{}'", listed++ ? ", " : "", name ? name : "");
  }
  return listed ? out : "none";
}

// The hinge or slide joint `name` of the model, else the reply names the file's.
int FindJoint(const Api& api, const mjModel* m, const std::string& name) {
  const int joint = api.name2id(m, mjOBJ_JOINT, name.c_str());
  if (joint < 0 || (m->jnt_type[joint] != mjJNT_HINGE && m->jnt_type[joint] != mjJNT_SLIDE)) {
    ReplyError(fmt::format("no hinge or slide joint '{}' (the file's: {})", name, JointNames(api, m)));
  }
  return joint;
}

// Runs in the child: loads, simulates, replies, never returns.
[[noreturn]] void SimulateInChild(const std::string& path, const MujocoRun& run, const std::vector<double>& time,
                                  const std::vector<double>& effort) {
  const Api api = LoadApi();
  char error[1000] = "";
  mjModel* m = api.load_xml(path.c_str(), nullptr, error, sizeof error);
  if (m == nullptr) ReplyError(fmt::format("MuJoCo cannot load it: {}", error));
  const int drive = FindJoint(api, m, run.drive);
  int actuator = -1, actuators = 0;
  for (int a = 0; a < m->nu; ++a) {
    if (m->actuator_trntype[a] == mjTRN_JOINT && m->actuator_trnid[2 * a] == drive) {
      actuator = a;
      ++actuators;
    }
  }
  if (actuators != 1) {
    ReplyError(fmt::format("joint '{}' has {} actuators: the logged effort drives exactly one", run.drive, actuators));
  }
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
    if (first_warning[0] != '\0' || d->warning[mjWARN_BADQACC].number > 0 || !finite) {
      ReplyError(fmt::format("unstable: MuJoCo warned before t = {} s ({}): a smaller MuJoCo step, or an effort "
                             "or parameters that are not physical",
                             time[k + 1], first_warning[0] != '\0' ? first_warning : "a bad acceleration"));
    }
  }
  const int version = api.version();
  const std::string library = fmt::format("{}.{}.{}", version / 100, version / 10 % 10, version % 10);
  std::string reply = "R";
  reply += static_cast<char>(library.size());
  reply += library;
  reply.append(reinterpret_cast<const char*>(&gear), sizeof gear);
  reply.append(reinterpret_cast<const char*>(out.data()), out.size() * sizeof(double));
  ::_exit(WriteAll(STDOUT_FILENO, reply.data(), reply.size()) ? 0 : 1);
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
  limits.max_output_bytes = payload + 4096;
  const ChildOutcome outcome = RunInChild([&] { SimulateInChild(path, run, time, effort); }, limits);
  const std::string where = fmt::format("{} (joint '{}')", path, run.drive);
  if (!outcome.started) throw InputError(fmt::format("{}: cannot start the MuJoCo process", where));
  if (outcome.timed_out) throw InputError(fmt::format("{}: MuJoCo took longer than {} s", where, limits.seconds));
  const std::string& r = outcome.output;
  if (!r.empty() && r[0] == 'E') {
    const std::string message = r.substr(1, 2000);
    if (message.rfind("unstable", 0) == 0) throw IdentificationError(fmt::format("{}: {}", where, message));
    throw InputError(fmt::format("{}: {}", where, message));
  }
  if (!outcome.exited || outcome.exit_code != 0 || r.size() < 2 || r[0] != 'R') {
    throw InputError(fmt::format("{}: the MuJoCo process {}", where,
                                 outcome.signal != 0 ? fmt::format("died of signal {} (a file MuJoCo cannot read?)",
                                                                   outcome.signal)
                                                     : "failed"));
  }
  const std::size_t version_length = static_cast<unsigned char>(r[1]);
  if (r.size() != 2 + version_length + payload) {
    throw InputError(fmt::format("{}: the MuJoCo process replied {} bytes, not {}", where, r.size(),
                                 2 + version_length + payload));
  }
  MujocoRunResponse response;
  response.library = r.substr(2, version_length);
  const char* data = r.data() + 2 + version_length;
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
