#include "workflow/cdrive_identification.h"

#include <utility>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"
#include "workflow/cdrive_compensation.h"

namespace driveid {

double CDriveDefaultHalfWindow(CDriveFitKind kind) { return kind == CDriveFitKind::kFriction ? 0.01 : 0.005; }

bool CDriveIdentificationOptions::IsValid(std::string* error) const { return OptionCheck(error).Nested(fit); }

namespace {

// One panel per log (measured dots, model lines for both motors), then the
// residuals of the samples that entered the fit; the trace's rows.
void AddTraces(const std::vector<CDriveLog>& logs, const CDriveFitOutput& result,
               const CDriveIdentificationOptions& options, CDriveIdentification& run) {
  const bool friction = options.kind == CDriveFitKind::kFriction;
  run.trace_csv = "# cdrive-fit trace: measured and model motor torques [N m]; used = entered the fit\n";
  run.trace_csv += "log,t,tau_L_measured,tau_L_model,tau_R_measured,tau_R_model,used\n";
  PlotPanel residuals{"residual (measured - model) of the samples used in the fit", "residual torque [N m]", {}};
  for (std::size_t i = 0; i < logs.size(); ++i) {
    if (!options.trace && !options.plot) break;  // nothing asked for
    const CDriveTrace& trace = result.traces[i];
    PlotLine used_left{logs[i].path + " tau_L", {}, {}, false, true};
    PlotLine used_right{logs[i].path + " tau_R", {}, {}, false, true};
    for (std::size_t k = 0; k < trace.time.size(); ++k) {
      if (options.trace) {
        run.trace_csv += fmt::format("{},{},{},{:.7g},{},{:.7g},{}\n", i + 1, trace.time[k], trace.measured_left[k],
                                     trace.model_left[k], trace.measured_right[k], trace.model_right[k],
                                     trace.used[k] ? 1 : 0);
      }
      if (!trace.used[k]) continue;
      used_left.x.push_back(trace.time[k]);
      used_left.y.push_back(trace.measured_left[k] - trace.model_left[k]);
      used_right.x.push_back(trace.time[k]);
      used_right.y.push_back(trace.measured_right[k] - trace.model_right[k]);
    }
    run.panels.push_back({fmt::format("{} fit: {}", friction ? "friction" : "inertia", logs[i].path),
                          "motor torque [N m]",
                          {{"measured tau_L", trace.time, trace.measured_left, true},
                           {"model tau_L", trace.time, trace.model_left, false},
                           {"measured tau_R", trace.time, trace.measured_right, true},
                           {"model tau_R", trace.time, trace.model_right, false}}});
    residuals.lines.push_back(std::move(used_left));
    residuals.lines.push_back(std::move(used_right));
  }
  run.panels.push_back(std::move(residuals));
}

}  // namespace

CDriveIdentification IdentifyCDrive(const std::vector<CDriveLog>& logs, const ParameterFile& start,
                                    const std::string& path, const CDriveIdentificationOptions& given) {
  const CDriveSection* section = start.Find<CDriveSection>();
  if (!section) throw InputError(fmt::format("{}: no 'cdrive' section", path));
  CDriveIdentificationOptions options = given;
  options.fit.traces = options.trace || options.plot;
  RequireValid(options);
  const bool friction = options.kind == CDriveFitKind::kFriction;
  const CDriveFitOutput result = friction ? FitCDriveFriction(logs, *section, options.fit)
                                          : FitCDriveInertia(logs, *section, options.fit);
  CDriveIdentification run;
  run.section = result.section;
  run.fit = result.fit;
  run.derived = result.derived;
  run.model = friction ? "cdrive friction (28)" : "cdrive inertia (17), (28)";
  if (friction) {
    // Eq. (31) as a controller loads it, with the fit's uncertainty (docs/models.md#c-drive).
    const auto* control = start.Find<CDriveControlSection>();
    run.feedforward = CalcCDriveCompensation(
        MakeModelParameters(CDriveParameterTable(), result.section, CDriveParameters{}, "cdrive"),
        control ? MakeControlSettings(*control) : CDriveControlSettings{}, result.fit);  // seed's DZ, RL by default
  }
  AddTraces(logs, result, options, run);
  return run;
}

}  // namespace driveid
