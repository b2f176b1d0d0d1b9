// Derived quantities of a drive-train parameter set (drivetrain-fit report):
// eq. (16) coefficients, omega_n, zeta, gain, steady state of the paper's
// experiment, and the paper's printed eq. (17) numbers beside the recomputed
// ones with the misprints called out (docs/models.md#drive-train).
#pragma once

#include <string>

#include "models/drivetrain.h"
#include "report/json.h"

namespace driveid {

/// Text report; `source` names the parameter file. With `fitted` non-null a
/// further column shows the same quantities for a fitted parameter set.
std::string FormatDriveTrainReport(const DriveTrainParameters& params, const std::string& source,
                                   const DriveTrainParameters* fitted = nullptr, const std::string& fitted_source = "");

/// The same as a JSON object.
Json DriveTrainReportJson(const DriveTrainParameters& params, const std::string& source,
                          const DriveTrainParameters* fitted = nullptr);

}  // namespace driveid
