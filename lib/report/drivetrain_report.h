// Derived quantities of a drive-train parameter set (drivetrain-fit report):
// eq. (16) coefficients, omega_n, zeta, gain, steady state of the paper's
// experiment, and the paper's printed eq. (17) numbers beside the recomputed
// ones with the misprints called out (SPEC 5.1, 8).
#pragma once

#include <string>

#include "models/drivetrain.h"

namespace driveid {

/// Text report; `source` names the parameter file.
std::string FormatDriveTrainReport(const DriveTrainParameters& params, const std::string& source);

/// The same as one JSON object.
std::string FormatDriveTrainReportJson(const DriveTrainParameters& params, const std::string& source);

}  // namespace driveid
