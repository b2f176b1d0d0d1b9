#include "cdrive_fit/fit_command.h"

#include <fmt/format.h>

#include "common/command_registry.h"
#include "core/errors.h"
#include "logs/csv_log.h"
#include "params/parameter_file.h"

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
  const ParameterFile start = ReadParameterFile(options.params);
  if (!start.Find<CDriveSection>()) throw InputError(fmt::format("{}: no 'cdrive' section", options.params));

  FitOutputs outputs;
  outputs.provenance.command = command_line;
  outputs.provenance.version = DRIVEID_VERSION;
  const auto logs = LoadLogs<CDriveLog>(options.logs, options.input, options.output, outputs.provenance, CDriveLogColumns(),
                                        [&](CsvLog csv) { return MakeCDriveLog(std::move(csv), start.Find<CDriveSection>()->torque_constant.value_or(0.0)); });

  CDriveIdentificationOptions run_options;
  run_options.kind = options.kind;
  CDriveFitOptions& fit_options = run_options.fit;
  fit_options.free = options.free;
  fit_options.half_window = options.window > 0.0 ? options.window : CDriveDefaultHalfWindow(options.kind);
  fit_options.min_rate = options.min_rate;
  fit_options.settle = options.settle;  // < 0: the fit's default
  SetProgress(fit_options.fit, options.output.verbose, options.output.max_seconds);
  run_options.trace = !options.output.trace.empty();
  run_options.plot = !options.output.plot.empty();
  CDriveIdentification run = IdentifyCDrive(logs, start, options.params, run_options);

  ParameterFile fitted = start;
  fitted.Set(run.section);
  if (run.feedforward) fitted.feedforward = std::move(*run.feedforward);
  outputs.provenance.model = run.model;
  outputs.fit = run.fit;
  outputs.parameter_file = FormatParameterFile(fitted, &outputs.fit, &outputs.provenance, run.derived);
  outputs.trace_csv = std::move(run.trace_csv);
  outputs.plot_panels = std::move(run.panels);
  EmitFitOutputs(options.output, outputs);
}

namespace {
const bool kFriction = RegisterCommand(Command<CDriveFitCommandOptions>(
    "cdrive-fit", "", 10, [](CLI::App& parent, CDriveFitCommandOptions& o) { return SetupCDriveFitCommand(parent, o, CDriveFitKind::kFriction); },
    [](const CDriveFitCommandOptions& o, const std::string& line) { RunCDriveFitCommand(o, line); }));
const bool kInertia = RegisterCommand(Command<CDriveFitCommandOptions>(
    "cdrive-fit", "", 20, [](CLI::App& parent, CDriveFitCommandOptions& o) { return SetupCDriveFitCommand(parent, o, CDriveFitKind::kInertia); },
    [](const CDriveFitCommandOptions& o, const std::string& line) { RunCDriveFitCommand(o, line); }));
}  // namespace

}  // namespace driveid::cli
