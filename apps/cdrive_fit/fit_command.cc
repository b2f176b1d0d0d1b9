#include "cdrive_fit/fit_command.h"

#include <fmt/format.h>

#include "common/command_registry.h"
#include "core/errors.h"
#include "fit/cdrive_fit.h"
#include "io/csv_log.h"
#include "io/parameter_file.h"
#include "workflow/cdrive_compensation.h"

namespace driveid::cli {

CLI::App* SetupCDriveFitCommand(CLI::App& app, CDriveFitCommandOptions& options, CDriveFitKind kind) {
  const bool friction = kind == CDriveFitKind::kFriction;
  options.kind = kind;
  CLI::App* command = app.add_subcommand(
      friction ? "friction" : "inertia",
      friction ? "Fit the dissipation parameters beta, gamma, delta, eta from slow-motion logs (inertia from --params)"
               : "Fit the inertia I_h, I_c, m (a and b of eq. 17) from fast-motion logs (friction from --params)");
  command->add_option("logs", options.logs, "C-drive logs (CSV, MAT; docs/formats.md#logs) with t, psi_L, psi_R, tau_L, tau_R (or i_L, i_R)")
      ->required();
  command->add_option("--params", options.params, "parameter file with a cdrive section")->required();
  AddFreeOption(*command, options.free,
                FreeOptionHelp(CDriveParameterTable(), friction ? "friction" : "inertia",
                               friction ? "" : "; all three of I_h, I_c, m are not identifiable"));
  AddLogInputOptions(*command, options.input, "psi_L=encoder_left");
  command->add_option("--window", options.window,
                      friction ? "half window of the zero-phase differentiator [s] (default 0.01)"
                               : "half window of the zero-phase differentiator [s] (default 0.005)")
      ->check(FiniteAbove(0.0));
  command->add_option("--min-rate", options.min_rate,
                      "use samples whose motor rates (and their difference, for the collar) exceed this [rad/s]")
      ->capture_default_str()
      ->check(FiniteAtLeast(0.0));
  command->add_option("--settle", options.settle,
                      "also leave out this long around each reversal (stick/slip and controller transients) [s] "
                      "(default 0.1 for friction, 0 for inertia)")
      ->check(FiniteAtLeast(0.0));
  AddFitOutputOptions(*command, options.output);
  command->footer(friction ? "Example:\n  cdrive-fit friction data/cdrive_slow_translation.csv data/cdrive_slow_rotation.csv "
                             "data/cdrive_slow_helical.csv \\\n      --params data/cdrive_table1.yaml -o friction.yaml --plot friction.png"
                           : "Example:\n  cdrive-fit inertia data/cdrive_fast_translation.csv data/cdrive_fast_rotation.csv "
                             "data/cdrive_fast_helical.csv \\\n      --params data/cdrive_table1.yaml --free I_h,I_c -o inertia.yaml");
  return command;
}

void RunCDriveFitCommand(const CDriveFitCommandOptions& options, const std::string& command_line) {
  CheckFitOutputs(options.output, LogCommandInputs(options.logs, options.params, options.input));
  const bool friction = options.kind == CDriveFitKind::kFriction;
  const ParameterFile start = ReadParameterFile(options.params);
  if (!start.Find<CDriveSection>()) throw InputError(fmt::format("{}: no 'cdrive' section", options.params));

  FitOutputs outputs;
  outputs.provenance.command = command_line;
  outputs.provenance.version = DRIVEID_VERSION;
  outputs.provenance.model = friction ? "cdrive friction (28)" : "cdrive inertia (17), (28)";
  const auto logs = LoadLogs<CDriveLog>(options.logs, options.input, options.output, outputs.provenance, CDriveLogColumns(),
                                        [&](CsvLog csv) { return MakeCDriveLog(std::move(csv), start.Find<CDriveSection>()->torque_constant.value_or(0.0)); });

  CDriveFitOptions fit_options;
  fit_options.free = options.free;
  fit_options.half_window = options.window > 0.0 ? options.window : (friction ? 0.01 : 0.005);
  fit_options.min_rate = options.min_rate;
  fit_options.settle = options.settle;  // < 0: the fit's default
  fit_options.traces = !options.output.trace.empty() || !options.output.plot.empty();
  SetProgress(fit_options.fit, options.output.verbose, options.output.max_seconds);
  const CDriveFitOutput result = friction ? FitCDriveFriction(logs, *start.Find<CDriveSection>(), fit_options)
                                          : FitCDriveInertia(logs, *start.Find<CDriveSection>(), fit_options);

  ParameterFile fitted = start;
  fitted.Set(result.section);
  outputs.fit = result.fit;
  if (friction) {
    // Eq. (31) as a controller loads it, with the fit's uncertainty (docs/models.md#c-drive).
    const auto* control = start.Find<CDriveControlSection>();
    fitted.feedforward = CalcCDriveCompensation(
        MakeModelParameters(CDriveParameterTable(), result.section, CDriveParameters{}, "cdrive"),
        control ? MakeControlSettings(*control) : CDriveControlSettings{}, result.fit);  // seed's DZ, RL by default
  }
  outputs.parameter_file = FormatParameterFile(fitted, &outputs.fit, &outputs.provenance, result.derived);
  outputs.trace_csv = "# cdrive-fit trace: measured and model motor torques [N m]; used = entered the fit\n";
  outputs.trace_csv += "log,t,tau_L_measured,tau_L_model,tau_R_measured,tau_R_model,used\n";
  // One panel per log (measured dots, model lines for both motors), then the
  // residuals of the samples that entered the fit.
  PlotPanel residuals{"residual (measured - model) of the samples used in the fit", "residual torque [N m]", {}};
  for (std::size_t i = 0; i < logs.size(); ++i) {
    if (options.output.trace.empty() && options.output.plot.empty()) break;  // nothing asked for
    const CDriveTrace& trace = result.traces[i];
    PlotLine used_left{logs[i].path + " tau_L", {}, {}, false, true};
    PlotLine used_right{logs[i].path + " tau_R", {}, {}, false, true};
    for (std::size_t k = 0; k < trace.time.size(); ++k) {
      if (!options.output.trace.empty()) outputs.trace_csv += fmt::format("{},{},{},{:.7g},{},{:.7g},{}\n", i + 1, trace.time[k], trace.measured_left[k],
                                       trace.model_left[k], trace.measured_right[k], trace.model_right[k],
                                       trace.used[k] ? 1 : 0);
      if (!trace.used[k]) continue;
      used_left.x.push_back(trace.time[k]);
      used_left.y.push_back(trace.measured_left[k] - trace.model_left[k]);
      used_right.x.push_back(trace.time[k]);
      used_right.y.push_back(trace.measured_right[k] - trace.model_right[k]);
    }
    outputs.plot_panels.push_back(
        {fmt::format("{} fit: {}", friction ? "friction" : "inertia", logs[i].path), "motor torque [N m]",
         {{"measured tau_L", trace.time, trace.measured_left, true},
          {"model tau_L", trace.time, trace.model_left, false},
          {"measured tau_R", trace.time, trace.measured_right, true},
          {"model tau_R", trace.time, trace.model_right, false}}});
    residuals.lines.push_back(std::move(used_left));
    residuals.lines.push_back(std::move(used_right));
  }
  outputs.plot_panels.push_back(std::move(residuals));
  EmitFitOutputs(options.output, outputs);
}

namespace {
CDriveFitCommandOptions friction_options, inertia_options;
const bool kFriction = RegisterCommand(
    {"cdrive-fit", "", 10,
     [](CLI::App& parent) { return SetupCDriveFitCommand(parent, friction_options, CDriveFitKind::kFriction); },
     [](const std::string& line) { RunCDriveFitCommand(friction_options, line); }});
const bool kInertia = RegisterCommand(
    {"cdrive-fit", "", 20,
     [](CLI::App& parent) { return SetupCDriveFitCommand(parent, inertia_options, CDriveFitKind::kInertia); },
     [](const std::string& line) { RunCDriveFitCommand(inertia_options, line); }});
}  // namespace

}  // namespace driveid::cli
