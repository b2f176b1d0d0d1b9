// What runs MuJoCo in a child process shares (sim/mujoco_axis_simulator.h,
// sim/mujoco_inverse.h): the library loaded with dlopen, its functions,
// its errors and first warning caught, the reply on the child's standard
// output ('E' and a message, or 'R' and the payload), and joints found by
// name. Only in a build with MuJoCo (DRIVEID_HAVE_MUJOCO).
#pragma once

#if defined(DRIVEID_HAVE_MUJOCO)
#include <functional>
#include <string>

#include <mujoco/mujoco.h>

#include "system/child_process.h"

namespace driveid::mujoco_child {

/// Replies 'E' and `message`, then ends the child.
[[noreturn]] void ReplyError(const std::string& message);
/// Replies 'R', the MuJoCo version text (one length byte, then the text) and `payload`, then ends the child.
[[noreturn]] void ReplyResult(const std::string& version, const std::string& payload);

struct Api {
  int (*version)();
  mjModel* (*load_xml)(const char*, const mjVFS*, char*, int);
  mjData* (*make_data)(const mjModel*);
  void (*forward)(const mjModel*, mjData*);
  void (*inverse)(const mjModel*, mjData*);
  void (*step)(const mjModel*, mjData*);
  int (*name2id)(const mjModel*, int, const char*);
  const char* (*id2name)(const mjModel*, int, int);
};

/// Loads the library (replying an error when it cannot) and installs the
/// error and warning handlers.
Api LoadApi();
/// The model at `path`, or an error reply quoting MuJoCo.
mjModel* LoadModel(const Api& api, const std::string& path);
/// MuJoCo's first warning since LoadApi, or empty.
const char* FirstWarning();
/// "2.2.2" of the loaded library.
std::string VersionText(const Api& api);

/// The hinge and slide joints' names, quoted, for a message ("none").
std::string JointNames(const Api& api, const mjModel* m);
/// The hinge or slide joint `name`, else an error reply naming the file's.
int FindJoint(const Api& api, const mjModel* m, const std::string& name);
/// The one actuator with a joint transmission on `joint`, else an error reply.
int JointActuator(const mjModel* m, int joint, const std::string& name);

/// Parent side: runs `child` (which ends in ReplyError or ReplyResult)
/// with `limits`, and returns the result's payload (`version` set), which
/// must be `payload_bytes` long (with `exact` false: at most that long). Throws InputError starting with `where`
/// for a child that failed, timed out or replied an error, except an error
/// starting with "unstable", thrown as IdentificationError.
std::string RunMujocoChild(const std::function<void()>& child, const ChildLimits& limits, const std::string& where,
                           std::size_t payload_bytes, std::string* version, bool exact = true);

}  // namespace driveid::mujoco_child
#endif
