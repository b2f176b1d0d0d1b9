// The drive-train step fit as `drivetrain-fit step` runs it
// (docs/models.md#drive-train): the fit of all logs, the held-out logs
// predicted with its estimates, the trace and plot data. The command parses,
// loads the logs, calls this, emits.
#pragma once

#include <string>
#include <vector>

#include "core/fit_result.h"
#include "fit/step/step_fit.h"
#include "logs/step_log.h"
#include "models/drivetrain.h"
#include "report/plot.h"

namespace driveid {

struct StepIdentificationOptions {
  StepFitOptions fit;
  bool trace = false;  ///< build the trace CSV
  bool plot = false;   ///< build the plot series
  /// Every bound on these fields (‹field› names the option); see core/option_check.h.
  bool IsValid(std::string* error) const;
};

struct StepIdentification {
  DriveTrainParameters params;     ///< the start values with the estimates put in
  FitResult fit;                   ///< with the held-out logs' validation
  std::string model;               ///< for the provenance: "reduced" or "full" (and the integration if not exact)
  std::string trace_csv;           ///< when asked for
  std::vector<PlotSeries> series;  ///< measured and model link torque per log, when asked for
  PlotLabels labels;
};

/// Fits `logs` from `start` and predicts `validation` (held-out logs) with
/// the estimates. Throws as FitStepResponses.
StepIdentification IdentifySteps(const std::vector<StepLog>& logs, const DriveTrainParameters& start,
                                 const StepIdentificationOptions& options, const std::vector<StepLog>& validation);

}  // namespace driveid
