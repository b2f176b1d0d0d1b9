#include "drivetrain_fit/axis_command.h"

#include <algorithm>
#include <cstdio>

#include <fmt/format.h>

#include "common/command_registry.h"
#include "core/errors.h"
#include "logs/csv_log.h"
#include "params/parameter_file.h"
#include "workflow/axis_identification.h"

namespace driveid::cli {

CLI::App* SetupAxisCommand(CLI::App& app, AxisOptions& options) {
  CLI::App* command = app.add_subcommand(
      "axis", "Inertia, viscous and Coulomb friction and offset of a rigid axis by inverse dynamics (IDIM-LS) or output error (docs/models.md#axis)");
  command->add_option("logs", options.logs, "axis logs (CSV, MAT, SysId JSON; docs/formats.md#logs) with t, q and tau (or i with axis.k_t), optional qd")->required();
  command->add_option("--params", options.params, "parameter file with an axis section (start values, k_t, n_g)");
  AddFreeOption(*command, options.fit.free,
                FreeOptionHelp(AxisParameterTable(), "axis", " (rotary units; on a linear axis, --linear: kg, N s/m, N, m/s)"));
  AddLogInputOptions(*command, options.input, "q=pi/180*#2, tau=10*#14");
  command->add_option("--validate", options.validate,
                      "held-out logs (same columns) to predict with the fitted parameters: fit %, RMSE, lag-1 per log "
                      "(docs/models.md#validation)");
  command->add_option("--method", options.method,
                      "idim: inverse dynamics (IDIM-LS, torque from the differentiated position); oe: output error "
                      "(simulate from the logged torque with sticking Coulomb, fit position and qd; "
                      "docs/models.md#axis-output-error); auto: oe when every log's torque is held in steps")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "idim", "oe"}));
  command->add_flag("--linear", options.linear,
                    "a linear axis: q in m, forces in N; units kg, N s/m, N in every output, no cos q / sin q gravity "
                    "(the weight is a constant force: the offset). Also axis.linear: true in --params, and SysId logs "
                    "in Meters, Feet or Inches (docs/models.md#axis)");
  command->add_option("--cutoff", options.fit.cutoff,
                      "position low-pass cutoff [Hz] (default: from the data, docs/models.md#axis-cutoff-from-the-data)")
      ->check(FiniteAbove(0.0));
  command->add_option("--decimation", options.fit.decimation,
                      "parallel decimation factor (0: from the logs' rate and length, docs/models.md#axis-decimation)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000));
  command->add_option("--torque-timing", options.torque_timing,
                      "idim: when the logged torque acts. sampled: at its sample's instant (a measured current); "
                      "held: the command the drive holds until the next sample, as output error simulates it; a "
                      "number D in [-1, 1]: D samples after its stamp (held 0.5; -0.5 a command held since the last "
                      "sample, as ros2_control logs it); auto: D estimated from the data, its std in the intervals "
                      "(docs/models.md#torque-timing)")
      ->capture_default_str()
      ->check(TorqueTimingText());
  AddFitOutputOptions(*command, options.output);
  command->footer(
      "Example:\n  drivetrain-fit simulate axis --params data/axis_example.yaml --noise 0.05 -o axis.csv\n"
      "  drivetrain-fit axis axis.csv -o axis_fit.yaml --plot axis_fit.png\n"
      "  (constant-rate logs: --free viscous,coulomb,offset)");
  return command;
}

AxisCommandResult ComputeAxisCommand(const AxisOptions& options, const std::string& command_line,
                                     std::vector<CsvLog> given) {
  ParameterFile start;
  if (!options.params.empty()) start = ReadParameterFile(options.params);
  AxisSection section = start.Find<AxisSection>() ? *start.Find<AxisSection>() : AxisSection{};
  section.linear = section.linear || options.linear;

  AxisCommandResult result;
  FitOutputs& outputs = result.outputs;
  outputs.provenance.command = command_line;
  outputs.provenance.version = DRIVEID_VERSION;
  std::vector<std::string> sysid_units;  // per log: the SysId file's units, "" for other logs
  std::vector<std::string> mechanisms;   // per log: the SysId file's test
  const auto make = [&](CsvLog csv) { return MakeAxisLog(std::move(csv), section.torque_constant.value_or(0.0)); };
  const auto take = [&](CsvLog csv) {
    sysid_units.push_back(csv.format == "sysid" || csv.format == "wpilog" ? csv.units : "");
    mechanisms.push_back(csv.mechanism);
    return make(std::move(csv));
  };
  std::vector<AxisLog> logs;
  if (given.empty()) {
    logs = LoadLogs<AxisLog>(options.logs, options.input, options.output, outputs.provenance, AxisLogColumns(), take);
  } else {
    for (CsvLog& csv : given) logs.push_back(take(std::move(csv)));
  }
  AxisIdentificationOptions fit_options;
  TakeSysIdDeclarations(sysid_units, mechanisms, fit_options);
  fit_options.method = options.method == "oe"     ? AxisMethod::kOutputError
                       : options.method == "idim" ? AxisMethod::kInverseDynamics
                                                  : AxisMethod::kAuto;
  const bool output_error = ChooseAxisMethod(logs, fit_options.method, nullptr) == AxisMethod::kOutputError;
  if (output_error && !options.validate.empty()) {
    throw OptionError("--validate predicts by inverse dynamics: use it with --method idim");
  }
  if (output_error && options.fit.cutoff > 0.0) {
    throw OptionError("--cutoff applies to --method idim only");
  }
  fit_options.axis = options.fit;
  fit_options.axis.torque_timing = ParseAxisTorqueTiming(options.torque_timing, fit_options.axis.torque_delay);
  fit_options.trace = !options.output.trace.empty();
  fit_options.simulate_rates = !options.output.plot.empty();
  SetProgress(fit_options.axis.fit, options.output.verbose, options.output.max_seconds);
  std::vector<AxisLog> validation;
  if (!options.validate.empty()) {
    FitProvenance held_out;
    validation = LoadLogs<AxisLog>(options.validate, options.input, options.output, held_out, AxisLogColumns(), make);
  }
  AxisIdentification run = IdentifyAxis(logs, section, fit_options, validation);

  outputs.provenance.model = run.model;
  ParameterFile fitted = start;
  fitted.Set(run.section);
  fitted.feedforward = run.feedforward;
  outputs.fit = run.fit;
  outputs.parameter_file = FormatParameterFile(fitted, &outputs.fit, &outputs.provenance, run.derived);
  outputs.trace_csv = run.trace_csv;
  if (!options.output.plot.empty()) {
    outputs.plot_panels = MakeFitPanels(run.series, run.labels);
    if (!run.rate_series.empty()) {
      outputs.plot_panels.push_back(MakeFitPanels(run.rate_series, {"rate: measured, and simulated by the fitted model from "
                                                                    "each log's start under its logged effort",
                                                                    "rate"}).front());
    }
  }
  result.summary = run.summary;
  return result;
}

void RunAxisCommand(const AxisOptions& options, const std::string& command_line) {
  CheckFitOutputs(options.output, LogCommandInputs(options.logs, options.params, options.input, options.validate));
  const AxisCommandResult result = ComputeAxisCommand(options, command_line);
  EmitFitOutputs(options.output, result.outputs);
  if (!options.output.quiet && !options.output.json) {
    std::FILE* summary = options.output.output.empty() ? stderr : stdout;
    for (const auto& line : result.summary) WriteText(summary, line + "\n");
  }
}

namespace {
const bool kRegistered = RegisterCommand(Command<AxisOptions>(
    "drivetrain-fit", "", 20, [](CLI::App& parent, AxisOptions& o) { return SetupAxisCommand(parent, o); },
    [](const AxisOptions& o, const std::string& line) { RunAxisCommand(o, line); }));
}  // namespace

}  // namespace driveid::cli
