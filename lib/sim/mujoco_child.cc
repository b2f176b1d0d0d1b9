#include "sim/mujoco_child.h"

#if defined(DRIVEID_HAVE_MUJOCO)
#include <cstdio>

#include <dlfcn.h>
#include <unistd.h>

#include <fmt/format.h>

#include "core/errors.h"

namespace driveid::mujoco_child {
namespace {

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

}  // namespace

void ReplyError(const std::string& message) {
  const std::string reply = "E" + message;
  WriteAll(STDOUT_FILENO, reply.data(), reply.size());
  ::_exit(0);
}

void ReplyResult(const std::string& version, const std::string& payload) {
  std::string reply = "R";
  reply += static_cast<char>(version.size());
  reply += version;
  reply += payload;
  ::_exit(WriteAll(STDOUT_FILENO, reply.data(), reply.size()) ? 0 : 1);
}

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
  api.inverse = Symbol<void (*)(const mjModel*, mjData*)>(library, "mj_inverse");
  api.step = Symbol<void (*)(const mjModel*, mjData*)>(library, "mj_step");
  api.name2id = Symbol<int (*)(const mjModel*, int, const char*)>(library, "mj_name2id");
  api.id2name = Symbol<const char* (*)(const mjModel*, int, int)>(library, "mj_id2name");
  if (api.version() != mjVERSION_HEADER) {
    ReplyError(fmt::format("MuJoCo library version {} differs from the header driveid was built with ({}): rebuild",
                           api.version(), mjVERSION_HEADER));
  }
  return api;
}

mjModel* LoadModel(const Api& api, const std::string& path) {
  char error[1000] = "";
  mjModel* m = api.load_xml(path.c_str(), nullptr, error, sizeof error);
  if (m == nullptr) ReplyError(fmt::format("MuJoCo cannot load it: {}", error));
  return m;
}

const char* FirstWarning() { return first_warning; }

std::string VersionText(const Api& api) {
  const int version = api.version();
  return fmt::format("{}.{}.{}", version / 100, version / 10 % 10, version % 10);
}

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

int FindJoint(const Api& api, const mjModel* m, const std::string& name) {
  const int joint = api.name2id(m, mjOBJ_JOINT, name.c_str());
  if (joint < 0 || (m->jnt_type[joint] != mjJNT_HINGE && m->jnt_type[joint] != mjJNT_SLIDE)) {
    ReplyError(fmt::format("no hinge or slide joint '{}' (the file's: {})", name, JointNames(api, m)));
  }
  return joint;
}

int JointActuator(const mjModel* m, int joint, const std::string& name) {
  int actuator = -1, actuators = 0;
  for (int a = 0; a < m->nu; ++a) {
    if (m->actuator_trntype[a] == mjTRN_JOINT && m->actuator_trnid[2 * a] == joint) {
      actuator = a;
      ++actuators;
    }
  }
  if (actuators != 1) {
    ReplyError(fmt::format("joint '{}' has {} actuators: the logged effort drives exactly one", name, actuators));
  }
  return actuator;
}

std::string RunMujocoChild(const std::function<void()>& child, const ChildLimits& limits, const std::string& where,
                           std::size_t payload_bytes, std::string* version, bool exact) {
  ChildLimits bounded = limits;
  bounded.max_output_bytes = payload_bytes + 4096;
  const ChildOutcome outcome = RunInChild(child, bounded);
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
  const std::size_t expected = 2 + version_length + payload_bytes;
  if (exact ? r.size() != expected : (r.size() < 2 + version_length || r.size() > expected)) {
    throw InputError(fmt::format("{}: the MuJoCo process replied {} bytes, {} {}", where, r.size(),
                                 exact ? "not" : "more than", expected));
  }
  *version = r.substr(2, version_length);
  return r.substr(2 + version_length);
}

}  // namespace driveid::mujoco_child
#endif
