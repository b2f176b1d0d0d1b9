#include "workflow/robot_identification.h"

#include <fmt/format.h>

#include "core/option_check.h"

namespace driveid {

bool RobotIdentificationOptions::IsValid(std::string* error) const { return OptionCheck(error).Nested(fit); }

RobotIdentification IdentifyRobot(const std::vector<RobotLog>& logs, const PlanarRobotParameters& start,
                                  const RobotIdentificationOptions& options) {
  RequireValid(options);
  const RobotFitOutput result = FitRobot(logs, start, options.fit);
  RobotIdentification run;
  run.params = result.params;
  run.fit = result.fit;
  // Trace: the current prediction per motor, split as in seed 000 Fig. 7.
  run.trace_csv = "# motor currents [A]: measured, its motion (minimum-norm) part, and the model split into "
                  "inertia, centrifugal/Coriolis and friction (seed 000 Fig. 7)\n";
  run.trace_csv += "log,t,motor,i_measured,i_motion,i_model,i_inertia,i_coriolis,i_friction\n";
  for (std::size_t l = 0; l < result.predictions.size() && options.trace; ++l) {
    const auto& p = result.predictions[l];
    for (std::size_t k = 0; k < p.time.size(); ++k) {
      for (std::size_t i = 0; i < 3; ++i) {
        run.trace_csv += fmt::format("{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}\n", l + 1, p.time[k], i + 1,
                                     p.measured[i][k], p.measured_motion[i][k], p.total[i][k], p.inertia[i][k],
                                     p.coriolis[i][k], p.friction[i][k]);
      }
    }
  }
  // Plot: motor 1 of the first log as in Fig. 7, then the residuals of all motors.
  const auto& first = result.predictions.front();
  PlotPanel figure{fmt::format("motor 1 current along {} (seed 000 Fig. 7)", logs.front().path), "current [A]",
                   {{"measured (motion part)", first.time, first.measured_motion[0], true},
                    {"model total", first.time, first.total[0], false},
                    {"inertia", first.time, first.inertia[0], false},
                    {"centrifugal/Coriolis", first.time, first.coriolis[0], false},
                    {"friction", first.time, first.friction[0], false}}};
  PlotPanel residual{"residual (measured motion part - model)", "current [A]", {}};
  for (std::size_t i = 0; i < 3; ++i) {
    std::vector<double> difference(first.time.size());
    for (std::size_t k = 0; k < difference.size(); ++k) difference[k] = first.measured_motion[i][k] - first.total[i][k];
    residual.lines.push_back({fmt::format("motor {}", i + 1), first.time, std::move(difference), false, true});
  }
  run.panels = {figure, residual};
  return run;
}

}  // namespace driveid
