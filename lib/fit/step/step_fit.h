// Output-error identification of the drive train (docs/models.md#drive-train) from logged
// motor-torque steps: simulate the stick/slip model with CVODES (one run per
// log and evaluation, sensitivities for the Jacobian), fit with the core of
// fit/least_squares. Several logs are fit jointly and share the drive-train
// parameters; `offset` adds a constant strain-gauge bias per log.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "fit/core/least_squares.h"
#include "fit/step/step_residuals.h"
#include "logs/step_log.h"
#include "models/drivetrain.h"
#include "sim/drivetrain_simulator.h"

namespace driveid {



/// Where the fit starts (docs/models.md#drive-train, "Starting on long
/// logs"): kStaged (default) fits the reduced model, then (full model) the
/// full model, to each log's first transient and starts the fit of the whole
/// logs there (on short logs, whose first transient is the whole log, the
/// reduced model starts from the given values directly); kBoth also fits
/// from the given values and keeps the lower cost, reporting a disagreement;
/// kGiven starts from the given values only.
enum class StepStarts { kStaged, kBoth, kGiven };

struct StepFitOptions {
  DriveTrainModel model = DriveTrainModel::kReduced;
  StepStarts starts = StepStarts::kStaged;
  std::vector<std::string> free = FitParameterKeys(DriveTrainParameterTable(), "step", true);  ///< may include "offset"
  FitOptions fit;
  /// How the simulations are integrated (sim/drivetrain_simulator.h).
  DriveTrainIntegration integration = DriveTrainIntegration::kExact;
  /// Every bound on these fields (‹field› names the option); see core/option_check.h.
  bool IsValid(std::string* error) const;
};

struct StepFitOutput {
  DriveTrainParameters params;              ///< start values with the estimates put in
  std::vector<double> offsets;              ///< per log [N m] (0 when not free)
  FitResult fit;
  std::vector<std::vector<double>> simulated;  ///< model link torque per log, offset included
};

/// Fits the free parameters to all logs jointly. Throws OptionError
/// for an unknown name in `free`, InputError for unusable start values and
/// IdentificationError when the data cannot determine the free parameters.
StepFitOutput FitStepResponses(const std::vector<StepLog>& logs, const DriveTrainParameters& start,
                               const StepFitOptions& options);

}  // namespace driveid
