// An axis written as MJCF (docs/export.md, or any MuJoCo model with a hinge or
// slide joint driven by one actuator) simulated in MuJoCo from a logged
// effort: the actuator's ctrl is the effort held on [t_k, t_{k+1}), the
// state starts at (q0, v0) at time[0], and q, v are sampled at t_k before
// the new ctrl applies (as sim/axis_simulator.h). Other joints of the model
// start at their reference pose with zero ctrl.
// MuJoCo steps with the file's integrator at h = (t_{k+1} - t_k) / n, n the
// smallest count with h <= max_step (docs/export.md#validation-in-mujoco:
// MuJoCo asks for a time step at most half its constraints' time constant,
// solref 0.02 s by default, so 1 ms is ten times inside; joint damping is
// implicit in its Euler integrator).
// MuJoCo ends its process on an error, and its XML parser trusts the file:
// it runs in a child process (system/child_process.h) that loads libmujoco with
// dlopen, so a tool that does not simulate in MuJoCo never maps it.
#pragma once

#include <string>
#include <vector>

namespace driveid {

struct MujocoAxisOptions {
  std::string joint = "axis";  ///< the joint's name in the MJCF
  double max_step = 1e-3;      ///< largest MuJoCo time step [s], > 0
  /// Every bound on these fields (‹field› names the option); see core/option_check.h.
  bool IsValid(std::string* error) const;
};

struct MujocoAxisResponse {
  std::vector<double> position, rate;  ///< q(t_k), v(t_k) of the joint
  std::string library;                 ///< MuJoCo's version, e.g. "2.2.2"
};

/// A run of any MJCF: `drive` is the joint driven through its one actuator
/// by the logged effort; `record` the joints whose state is set at the start
/// and sampled. A joint `per_gear` is given and sampled in the actuator's
/// input units (a motor angle q_motor for a joint on the link side: the
/// child divides by the actuator's gear n and multiplies back).
struct MujocoJointStart {
  std::string joint;
  double position = 0.0, rate = 0.0;
  bool per_gear = false;
};

struct MujocoRun {
  std::string drive;
  std::vector<MujocoJointStart> record;
  double max_step = 1e-3;  ///< largest MuJoCo time step [s], > 0
  /// Wall-clock budget [s]: the child times its first steps on this model
  /// and refuses (naming the projected time) a run that would exceed it.
  double max_seconds = 600.0;
};

struct MujocoRunResponse {
  std::vector<std::vector<double>> position, rate;  ///< per recorded joint, at t_k
  double gear = 1.0;                                ///< the driving actuator's gear
  std::string library;
};

/// Whether this build can run MuJoCo (libmujoco-dev found when it was
/// built); else `why` says what is missing.
bool MujocoAvailable(std::string* why);

/// Simulates the MJCF at `path` as `run` says; errors as SimulateMujocoAxis.
MujocoRunResponse SimulateMujoco(const std::string& path, const MujocoRun& run, const std::vector<double>& time,
                                 const std::vector<double>& effort);

/// Simulates the MJCF at `path` (one joint, driven and recorded). Throws InputError (no MuJoCo in this
/// build, a file MuJoCo refuses, no such joint, not exactly one actuator on
/// it, the child process failing or taking too long) and IdentificationError
/// (the simulation becomes unstable), naming the file and the joint.
MujocoAxisResponse SimulateMujocoAxis(const std::string& path, const MujocoAxisOptions& options,
                                      const std::vector<double>& time, const std::vector<double>& effort, double q0,
                                      double v0);

}  // namespace driveid
