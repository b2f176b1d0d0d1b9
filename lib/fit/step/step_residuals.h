// The drive train's step-response residuals (docs/models.md#drive-train):
// simulated minus measured link torque of every log (and the logged angles,
// weighted, where the fit uses them), with the sensitivities as Jacobian;
// a long single log simulated in pieces as the solver asks for its rows.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "core/fit_result.h"
#include "fit/core/residual_model.h"
#include "logs/step_log.h"
#include "models/drivetrain.h"
#include "sim/drivetrain_simulator.h"

namespace driveid {

/// The step fit's residual model: simulated minus measured link torque of
/// every log, with the sensitivities to `free` (then one offset per log if
/// `fit_offsets`) as its Jacobian. `logs` must outlive it.
std::unique_ptr<ResidualModel> MakeStepResiduals(const std::vector<StepLog>& logs, const DriveTrainParameters& start,
                                                 DriveTrainModel model, std::vector<DriveTrainParameter> free,
                                                 bool fit_offsets);

/// The residuals the step fit itself uses (fit/step/step_fit.h): the angle
/// channels too, streamed when `large` says the problem is large.
class StepFitResiduals : public ResidualModel, public BlockResidualModel {
 public:
  virtual void set_integration(DriveTrainIntegration integration) = 0;
  /// Log i's model link torque (offset included) at `parameters`.
  virtual std::vector<double> Simulate(std::size_t i, const double* parameters) = 0;
  virtual std::vector<FitChannel> Channels() const = 0;
  /// The fit's rmse per channel in the channels' own units (the angles weighed back).
  virtual void UnweightRmse(FitResult& fit) const = 0;
};
std::unique_ptr<StepFitResiduals> MakeStepFitResiduals(const std::vector<StepLog>& logs,
                                                       const DriveTrainParameters& start, DriveTrainModel model,
                                                       std::vector<DriveTrainParameter> ode_parameters,
                                                       bool fit_offsets, const LargeProblemPolicy& large);

}  // namespace driveid
