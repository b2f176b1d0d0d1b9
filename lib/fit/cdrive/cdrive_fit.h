// Identification of the C-drive (docs/models.md#c-drive) from motor angles and torques by
// inverse-dynamics least squares:
//   friction: beta, gamma, delta, eta from slow programs, inertia from --params;
//   inertia:  I_h, I_c, m (only a and b of eq. 17 are identifiable) from fast
//             programs, friction from --params.
// Rates and accelerations come from the zero-phase local-polynomial
// differentiator. The equations are used as sum and difference of the two
// motors:
//   tau_L + tau_R = (a + b)(psi_L'' + psi_R'') + beta (psi_L' + psi_R') + delta (sgn psi_L' + sgn psi_R')
//   tau_L - tau_R = (a - b)(psi_L'' - psi_R'') + (beta + gamma)(psi_L' - psi_R')
//                   + delta (sgn psi_L' - sgn psi_R') + 2 eta sgn(psi_L' - psi_R')
// with a + b = I_h + I_c/2 and a - b = I_h + p^2 m/(8 pi^2). The collar terms
// appear only in the difference, so pure rotation (psi_L' = psi_R') cannot
// determine gamma and eta. A sum row is used only where both |psi_L'| and
// |psi_R'| exceed min_rate (the Coulomb signs are then certain; near a
// reversal the encoder staircase and static friction make them unknown); a
// difference row also needs |psi_L' - psi_R'| above it.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "fit/core/least_squares.h"
#include "logs/cdrive_log.h"
#include "models/cdrive.h"

namespace driveid {




struct CDriveFitOptions {
  std::vector<std::string> free;  ///< empty = the default of the fit
  double half_window = 0.01;      ///< differentiator half window [s] (doubled for accelerations that are regressors)
  double min_rate = 0.5;          ///< rate threshold for using a sample [rad/s]
  /// Also leave out this long around each slow stretch (stick/slip and
  /// controller transients after reversals) [s]; < 0 = 0.1 s for the friction
  /// fit (slow programs), 0 for the inertia fit (fast programs reverse often).
  double settle = -1.0;
  /// Whether the output holds the per-log traces (measured and model
  /// torques at every sample: memory of the order of the logs).
  bool traces = true;
  FitOptions fit;
  /// Whether the values can be used; else `error` names the field and the constraint.
  bool IsValid(std::string* error) const;
};

/// Per-log comparison of measured and model torques (model from (28) with
/// the fitted parameters and the estimated rates and accelerations).
struct CDriveTrace {
  std::vector<double> time;
  std::vector<double> measured_left, measured_right;
  std::vector<double> model_left, model_right;
  std::vector<char> used;  ///< 1 if the sample entered the fit (sum row)
};

struct CDriveFitOutput {
  CDriveSection section;                   ///< start values with the estimates put in
  FitResult fit;
  std::vector<DerivedQuantity> derived;    ///< a and b of eq. (17) for the inertia fit
  std::vector<CDriveTrace> traces;       ///< empty unless CDriveFitOptions::traces
  int rows_used = 0;
  int rows_possible = 0;
};

/// Fits beta, gamma, delta, eta (or the `free` subset) jointly over all logs.
/// With I_h, I_c, m given in `start` the inertial part is known; without
/// them a + b and a - b are estimated alongside (reported as a, b).
CDriveFitOutput FitCDriveFriction(const std::vector<CDriveLog>& logs, const CDriveSection& start,
                                  const CDriveFitOptions& options);

/// The torques (28) predicted from `params` at each log's samples, rates and
/// accelerations from the fit's differentiator (`options.half_window`);
/// `used` marks the samples a friction fit would use (both rates above
/// options.min_rate, clear of reversals by the window and 0.1 s, or
/// options.settle). For validation (fit/validation/validation.h).
std::vector<CDriveTrace> PredictCDriveTorques(const std::vector<CDriveLog>& logs, const CDriveParameters& params,
                                              const CDriveFitOptions& options);

/// Fits I_h, I_c, m (or the `free` subset; default I_h, I_c with m fixed)
/// with the friction coefficients from `start`. Reports a and b always.
CDriveFitOutput FitCDriveInertia(const std::vector<CDriveLog>& logs, const CDriveSection& start,
                                 const CDriveFitOptions& options);

}  // namespace driveid
