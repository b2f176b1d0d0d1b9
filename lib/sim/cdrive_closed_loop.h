// Closed-loop simulation of the C-drive (seed 001 sections IV.C-F): every
// controller period the 13-bit encoders are read, the controller
// (control/cdrive_controller) computes the motor torques from the program's
// reference, and the plant (sim/cdrive_plant) integrates (28) with sticking
// friction while the torques are held. Writes the log the rig would record
// (encoder angles, commanded torques) and the tracking errors in collar
// coordinates, u [m] and theta [rad], from the encoder angles as in the seed.
// Documented in docs/models.md#c-drive and docs/cli.md (cdrive-fit simulate).
#pragma once

#include <cstdint>
#include <vector>

#include "control/cdrive_control_settings.h"
#include "logs/cdrive_log.h"
#include "models/cdrive.h"
#include "sim/motion_program.h"

namespace driveid {

struct ClosedLoopOptions {
  MotionProgram program;
  int cycles = 1;            ///< forward-and-back cycles (each 2 T)
  double torque_noise = 0.0; ///< std of Gaussian noise added to the logged torques [N m]
  std::uint64_t seed = 1;
  /// Every bound on these fields (‹field› names the option); see core/option_check.h.
  bool IsValid(std::string* error) const;
};

struct TrackingTrace {
  std::vector<double> time;
  std::vector<double> translation_error;  ///< u_ref - u [m]
  std::vector<double> rotation_error;     ///< theta_ref - theta [rad]
};

struct ClosedLoopResult {
  CDriveLog log;
  TrackingTrace tracking;
  double endpoint_translation_error = 0.0;  ///< max |u error| at the stroke ends [m]
  double endpoint_rotation_error = 0.0;     ///< max |theta error| at the stroke ends [rad]
  double max_translation_error = 0.0;       ///< max |u error| over the run [m]
  double max_rotation_error = 0.0;          ///< [rad]
  int switches = 0;                         ///< stick/slip switches of the plant
};

/// Checks the options and settings; throws OptionError naming the
/// option, its value and the constraint.
void ValidateClosedLoop(const ClosedLoopOptions& options, const CDriveControlSettings& settings);

/// Runs the simulation. `params` is the plant and what the compensation uses.
ClosedLoopResult SimulateClosedLoop(const CDriveParameters& params, const CDriveControlSettings& settings,
                                    const ClosedLoopOptions& options);

}  // namespace driveid
