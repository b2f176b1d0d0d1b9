#include "workflow/step_identification.h"

#include <fmt/format.h>

#include "core/option_check.h"
#include "fit/validation/validation.h"

namespace driveid {

bool StepIdentificationOptions::IsValid(std::string* error) const { return OptionCheck(error).Nested(fit); }

StepIdentification IdentifySteps(const std::vector<StepLog>& logs, const DriveTrainParameters& start,
                                 const StepIdentificationOptions& options, const std::vector<StepLog>& validation) {
  RequireValid(options);
  const StepFitOutput result = FitStepResponses(logs, start, options.fit);
  StepIdentification run;
  run.params = result.params;
  run.fit = result.fit;
  for (const auto& v : ValidateSteps(validation, result.params, options.fit.model)) run.fit.validation.push_back(v.stats);
  const std::string model = options.fit.model == DriveTrainModel::kFull ? "full" : "reduced";
  run.model = model + (options.fit.integration == DriveTrainIntegration::kCvodes ? ", integrated by CVODES" : "");
  if (options.trace) {
    run.trace_csv = "# drivetrain-fit step trace: measured and model link torque [N m]\n";
    run.trace_csv += "log,t,tau_motor,tau_link_measured,tau_link_model,residual\n";
  }
  for (std::size_t i = 0; i < logs.size(); ++i) {
    const StepLog& log = logs[i];
    const auto& simulated = result.simulated[i];
    for (std::size_t k = 0; k < log.time.size() && options.trace; ++k) {
      run.trace_csv += fmt::format("{},{},{},{},{:.9g},{:.9g}\n", i + 1, log.time[k], log.motor_torque[k],
                                   log.link_torque[k], simulated[k], log.link_torque[k] - simulated[k]);
    }
    if (options.plot) run.series.push_back({log.path, log.time, log.link_torque, simulated});
  }
  run.labels = {fmt::format("drive-train step fit ({} model)", model), "link torque [N m]"};
  return run;
}

}  // namespace driveid
