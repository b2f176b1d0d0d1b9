// Parameter files (SPEC section 4): YAML with one section per model, plain
// values a controller can read, and a separate `fit` section with the
// statistics and provenance written by the fitting commands.
//
// Reading is strict: unknown keys, duplicate keys, non-numbers, NaN/Inf and
// out-of-range values throw InputError "file:line:column: section.key: what".
// Optional keys that are absent read as NaN ("not given").
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "control/cdrive_control_settings.h"
#include "core/fit_result.h"
#include "models/axis.h"
#include "models/cdrive.h"
#include "models/drivetrain.h"
#include "models/planar_robot.h"

namespace driveid {

/// The C-drive section: model parameters, the motor torque constant (for
/// logs of currents) and the controller settings.
struct CDriveSection {
  CDriveParameters params;
  double torque_constant = std::numeric_limits<double>::quiet_NaN();  ///< k_t [N m/A]
  std::optional<CDriveControlSettings> control;
};

/// The axis section: model parameters (NaN = not given), the torque
/// constant for logs of current, and an optional gear ratio (for d_g).
struct AxisSection {
  double inertia = std::numeric_limits<double>::quiet_NaN();          ///< J
  double viscous = std::numeric_limits<double>::quiet_NaN();          ///< b
  double coulomb = std::numeric_limits<double>::quiet_NaN();          ///< tau_c
  double offset = std::numeric_limits<double>::quiet_NaN();           ///< tau_0
  double torque_constant = std::numeric_limits<double>::quiet_NaN();  ///< k_t [N m/A]
  double gear_ratio = std::numeric_limits<double>::quiet_NaN();       ///< n_g [-]
  AxisParameters params() const { return {inertia, viscous, coulomb, offset}; }
  void set(const AxisParameters& p) {
    inertia = p.inertia;
    viscous = p.viscous;
    coulomb = p.coulomb;
    offset = p.offset;
  }
};

struct ParameterFile {
  std::optional<DriveTrainParameters> drivetrain;
  std::optional<AxisSection> axis;
  std::optional<PlanarRobotParameters> planar_robot;
  std::optional<CDriveSection> cdrive;
  bool had_fit_section = false;  ///< input carried a previous fit (replaced on output)
  /// fit.estimates of a previous fit (value, std, ci95), for reports.
  std::vector<ParameterEstimate> fit_estimates;
};

/// Parses YAML text; `path` is used in messages only.
ParameterFile ParseParameterFile(const std::string& path, const std::string& text);
/// Reads and parses a file.
ParameterFile ReadParameterFile(const std::string& path);

/// Formats a parameter file; with `fit`/`provenance` non-null a `fit`
/// section is added. Output is deterministic and reads back unchanged.
std::string FormatParameterFile(const ParameterFile& file, const FitResult* fit = nullptr,
                                const FitProvenance* provenance = nullptr,
                                const std::vector<DerivedQuantity>& derived = {});

/// True when a value was given (not NaN).
inline bool IsGiven(double value) { return value == value; }

}  // namespace driveid
