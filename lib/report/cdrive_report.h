// Report of a C-drive parameter set (cdrive-fit report): J, J^-1, J'J, the
// inertia matrix M and its isotropy, and a Table-I style table of the
// dissipation parameters beside the paper's, with standard errors when the
// file carries a fit.
#pragma once

#include <string>
#include <vector>

#include "core/fit_result.h"
#include <optional>

#include "control/cdrive_control_settings.h"
#include "models/cdrive.h"
#include "report/json.h"

namespace driveid {

std::string FormatCDriveReport(const CDriveSection& cdrive, const std::optional<CDriveControlSection>& control,
                               const std::vector<ParameterEstimate>& estimates, const std::string& source);

Json CDriveReportJson(const CDriveSection& cdrive, const std::vector<ParameterEstimate>& estimates,
                      const std::string& source);

}  // namespace driveid
