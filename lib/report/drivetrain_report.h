// Derived quantities of a drive-train parameter set (drivetrain-fit report):
// eq. (16) coefficients, omega_n, zeta, gain, steady state of the paper's
// experiment, and the paper's printed eq. (17) numbers beside the recomputed
// ones with the misprints called out (docs/models.md#drive-train).
#pragma once

#include <optional>
#include <string>

#include "models/drivetrain.h"
#include "report/json.h"

namespace driveid {

/// Quantities derived from one parameter set.
struct DriveTrainQuantities {
  ReducedTransferFunction tf;   ///< eq. (16): gain, a2, a1, omega_n, zeta
  double series_stiffness;      ///< k_eq [N m/rad]
  double stuck_level;           ///< link torque after the paper's -0.8 N m step, drive stuck [N m]
  double overshoot;             ///< relative overshoot of the sliding phase [-]
  double stuck_link_frequency;  ///< full model: link mode with the motor stuck [rad/s] (0: reduced)
};

/// The report: a parameter set (and optionally a fitted one) with their
/// derived quantities; rendered as text or JSON.
struct DriveTrainReport {
  std::string source;
  DriveTrainParameters params;
  DriveTrainQuantities recomputed;
  std::optional<DriveTrainParameters> fitted;
  std::optional<DriveTrainQuantities> fitted_quantities;
  std::string fitted_source;
};

DriveTrainQuantities CalcDriveTrainQuantities(const DriveTrainParameters& params);
/// `source` names the parameter file; `fitted` (may be null) a fitted set shown beside.
DriveTrainReport CalcDriveTrainReport(const DriveTrainParameters& params, const std::string& source,
                                      const DriveTrainParameters* fitted = nullptr,
                                      const std::string& fitted_source = "");

/// Text: the paper's printed numbers, the recomputed ones (and the fitted
/// ones), with the misprints called out.
std::string FormatDriveTrainReport(const DriveTrainReport& report);
/// The same as a JSON object.
Json DriveTrainReportJson(const DriveTrainReport& report);

}  // namespace driveid
