// The C-drive's friction compensation of seed 001 eq. (31) as a controller
// loads it (models/feedforward.h, law "cdrive"; docs/models.md#c-drive):
// beta, gamma_half = gamma / 2, delta, eta with the standard errors of the
// friction fit (gamma_half's halved), and the controller's dead zone and
// rate limit (settings: std 0).
#pragma once

#include "control/cdrive_control_settings.h"
#include "core/fit_result.h"
#include "models/cdrive.h"
#include "models/feedforward.h"

namespace driveid {

Feedforward CalcCDriveCompensation(const CDriveParameters& params, const CDriveControlSettings& control,
                                   const FitResult& fit);

}  // namespace driveid
