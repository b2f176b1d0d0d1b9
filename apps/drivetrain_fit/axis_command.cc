#include "drivetrain_fit/axis_command.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <optional>

#include <fmt/format.h>

#include "common/command_registry.h"
#include "core/errors.h"
#include "fit/axis_fit.h"
#include "fit/axis_oe_fit.h"
#include "fit/validation.h"
#include "io/csv_log.h"
#include "io/parameter_file.h"
#include "io/sha256.h"
#include "report/axis_feedforward.h"

namespace driveid::cli {

CLI::App* SetupAxisCommand(CLI::App& app, AxisOptions& options) {
  CLI::App* command = app.add_subcommand(
      "axis", "Inertia, viscous and Coulomb friction and offset of a rigid axis by inverse dynamics (IDIM-LS) or output error (docs/models.md#axis)");
  command->add_option("logs", options.logs, "axis logs (CSV, MAT, SysId JSON; docs/formats.md#logs) with t, q and tau (or i with axis.k_t), optional qd")->required();
  command->add_option("--params", options.params, "parameter file with an axis section (start values, k_t, n_g)");
  AddFreeOption(*command, options.free,
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
  command->add_option("--cutoff", options.cutoff,
                      "position low-pass cutoff [Hz] (default: from the data, docs/models.md#axis-cutoff-from-the-data)")
      ->check(FiniteAbove(0.0));
  command->add_option("--decimation", options.decimation, "parallel decimation factor")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  AddFitOutputOptions(*command, options.output);
  command->footer(
      "Example:\n  drivetrain-fit simulate axis --params data/axis_example.yaml --noise 0.05 -o axis.csv\n"
      "  drivetrain-fit axis axis.csv -o axis_fit.yaml --plot axis_fit.png\n"
      "  (constant-rate logs: --free viscous,coulomb,offset)");
  return command;
}

namespace {

// What either method leaves for the outputs.
struct AxisRun {
  AxisParameters params;
  FitResult fit;
  std::string trace_csv;
  std::vector<PlotSeries> series;
  PlotLabels labels;
  std::vector<std::string> summary;  // lines for the text summary
  std::vector<DerivedQuantity> derived;
};

AxisRun RunInverseDynamics(const std::vector<AxisLog>& logs, const AxisSection& section, const AxisOptions& options) {
  AxisFitOptions fit_options;
  fit_options.free = options.free;
  fit_options.cutoff = options.cutoff;
  fit_options.decimation = options.decimation;
  SetProgress(fit_options.fit, options.output.verbose);
  const AxisFitOutput result = FitAxis(logs, section, fit_options);
  AxisRun run{result.params, result.fit, {}, std::vector<PlotSeries>(logs.size()),
              {"axis IDIM-LS fit (filtered, decimated)", "force or torque"}, {}, {}};
  run.trace_csv = fmt::format("# drivetrain-fit axis trace: decimated samples used by IDIM-LS ({}, cutoff {} Hz)\n",
                              result.method, result.cutoff);
  run.trace_csv += "log,t,tau_measured,tau_model,residual\n";
  for (std::size_t i = 0; i < logs.size(); ++i) run.series[i].title = logs[i].path;
  for (std::size_t k = 0; k < result.time.size(); ++k) {
    const int i = result.log_index[k];
    if (!options.output.trace.empty()) {
      run.trace_csv += fmt::format("{},{},{:.7g},{:.7g},{:.7g}\n", i + 1, result.time[k], result.measured[k],
                                   result.model[k], result.measured[k] - result.model[k]);
    }
    auto& s = run.series[static_cast<std::size_t>(i)];
    s.time.push_back(result.time[k]);
    s.measured.push_back(result.measured[k]);
    s.model.push_back(result.model[k]);
  }
  if (!options.validate.empty()) {
    FitProvenance held_out;
    const auto validation_logs = LoadLogs<AxisLog>(
        options.validate, options.input, options.output, held_out, AxisLogColumns(),
        [&](CsvLog csv) { return MakeAxisLog(std::move(csv), section.torque_constant.value_or(0.0)); });
    for (const auto& v : ValidateAxis(validation_logs, result.params, result.cutoff, options.decimation)) {
      run.fit.validation.push_back(v.stats);
    }
  }
  run.summary.push_back(fmt::format("processing: {}", result.method));
  run.summary.push_back(fmt::format("relative error of the fit {:.2f} %, {} decimated samples, acceleration content "
                                    "{:.3g} 1/s",
                                    result.relative_error_percent, result.samples_used, result.acceleration_content));
  run.summary.push_back(fmt::format("position cutoff {:.4g} Hz ({})", result.cutoff, result.cutoff_rule));
  run.derived.push_back({"relative_error_percent", result.relative_error_percent, 0.0, "% |tau - model| / |tau|"});
  return run;
}

AxisRun RunOutputError(const std::vector<AxisLog>& logs, const AxisSection& section, const AxisOptions& options) {
  // Start values from inverse dynamics where it gives a usable inertia.
  std::optional<AxisParameters> initial;
  std::exception_ptr refused;
  try {
    // The linear terms only: the Stribeck pair is the output-error fit's.
    AxisFitOptions idim;
    idim.free.clear();
    for (const auto& key : options.free) {
      if (key != KeyOf(AxisParameterTable(), &AxisParameters::stribeck) &&
          key != KeyOf(AxisParameterTable(), &AxisParameters::stribeck_velocity)) {
        idim.free.push_back(key);
      }
    }
    idim.sensitivity = false;
    idim.per_log = false;
    AxisSection linear = section;
    linear.stribeck.reset();
    linear.stribeck_velocity.reset();
    const AxisFitOutput start = FitAxis(logs, linear, idim);
    if (start.params.inertia > 0.0) initial = start.params;
  } catch (const std::exception&) {
    // Inverse dynamics refused these logs: start from the parameter file,
    // or, without a start there, say why inverse dynamics refused them.
    refused = std::current_exception();
  }
  const bool inertia_free = std::find(options.free.begin(), options.free.end(),
                                      KeyOf(AxisParameterTable(), &AxisParameters::inertia)) != options.free.end();
  if (!initial && refused && inertia_free && !(section.inertia.value_or(0.0) > 0.0)) std::rethrow_exception(refused);
  AxisOeOptions oe_options;
  oe_options.free = options.free;
  SetProgress(oe_options.fit, options.output.verbose);
  const AxisOeOutput result = FitAxisOutputError(logs, section, initial ? &*initial : nullptr, oe_options);
  AxisRun run{result.params, result.fit, {}, std::vector<PlotSeries>(logs.size()),
              {"axis output-error fit (simulated from the logged torque)", "position"}, {}, {}};
  run.trace_csv = "# drivetrain-fit axis trace: output error, simulated from the logged torque\n";
  run.trace_csv += "log,t,q_measured,q_model,qd_measured,qd_model\n";
  for (std::size_t i = 0; i < logs.size(); ++i) {
    const AxisLog& log = logs[i];
    run.series[i] = {log.path, log.time, log.position, result.position[i]};
    for (std::size_t k = 0; k < log.time.size() && !options.output.trace.empty(); ++k) {
      run.trace_csv += fmt::format("{},{},{:.10g},{:.10g},{},{:.7g}\n", i + 1, log.time[k], log.position[k],
                                   result.position[i][k], log.rate.empty() ? "" : fmt::format("{:.7g}", log.rate[k]),
                                   result.rate[i][k]);
    }
  }
  run.summary.push_back(fmt::format("start values from {}", result.start_from));
  return run;
}

}  // namespace

void RunAxisCommand(const AxisOptions& options, const std::string& command_line) {
  CheckFitOutputs(options.output, LogCommandInputs(options.logs, options.params, options.input, options.validate));
  ParameterFile start;
  if (!options.params.empty()) start = ReadParameterFile(options.params);
  AxisSection section = start.Find<AxisSection>() ? *start.Find<AxisSection>() : AxisSection{};
  section.linear = section.linear || options.linear;

  FitOutputs outputs;
  outputs.provenance.command = command_line;
  outputs.provenance.version = DRIVEID_VERSION;
  std::vector<std::string> sysid_units;  // per log: the SysId file's units, "" for other logs
  const auto logs = LoadLogs<AxisLog>(options.logs, options.input, options.output, outputs.provenance, AxisLogColumns(),
                                        [&](CsvLog csv) {
                                          sysid_units.push_back(csv.format == "sysid" ? csv.units : "");
                                          return MakeAxisLog(std::move(csv), section.torque_constant.value_or(0.0));
                                        });
  // SysId logs in a length unit are of a linear mechanism (an elevator, a drivetrain).
  const bool sysid = std::all_of(sysid_units.begin(), sysid_units.end(),
                                 [&](const std::string& u) { return !u.empty() && u == sysid_units.front(); });
  if (sysid && IsLengthUnit(sysid_units.front())) section.linear = true;
  // The method (docs/models.md#axis-output-error): auto takes output error
  // when every log's torque is held in steps.
  std::string method = options.method, why = "--method " + options.method;
  if (method == "auto") {
    const bool steps = std::all_of(logs.begin(), logs.end(), [](const AxisLog& l) { return IsTorqueStepLog(l); });
    method = steps ? "oe" : "idim";
    why = steps ? "auto: the torque is held in steps (changes at < 2 % of the samples)"
                : "auto: the torque varies (changes at >= 2 % of the samples)";
  }
  if (method == "oe" && !options.validate.empty()) {
    throw OptionError("--validate predicts by inverse dynamics: use it with --method idim");
  }
  if (method == "oe" && options.cutoff > 0.0) throw OptionError("--cutoff applies to --method idim only");
  AxisRun run = method == "oe" ? RunOutputError(logs, section, options) : RunInverseDynamics(logs, section, options);
  outputs.provenance.model = method == "oe"
                                 ? "axis (docs/models.md#axis-output-error), output error (CVODES, sticking Coulomb)"
                                 : "axis (docs/models.md#axis), IDIM-LS";
  run.summary.insert(run.summary.begin(),
                     fmt::format("method: {} ({})", method == "oe" ? "output error" : "IDIM-LS", why));

  ParameterFile fitted = start;
  AxisSection out_section = section;
  StoreModelParameters(AxisParameterTable(), run.params, out_section);
  fitted.Set(out_section);
  // Units of the estimates, in the log's units (SysId: the feed-forward's;
  // else rotary or linear SI).
  for (auto& e : run.fit.estimates) {
    if (const auto* row = FindParameter(AxisParameterTable(), e.name)) {
      e.unit = sysid ? AxisUnitIn(row->spec, "V", sysid_units.front()) : AxisUnit(row->spec, section.linear);
    }
  }
  outputs.fit = run.fit;
  std::vector<DerivedQuantity> derived = run.derived;
  if (section.gear_ratio) {
    double viscous_std = 0.0;
    for (const auto& e : run.fit.estimates) {
      if (e.name == KeyOf(AxisParameterTable(), &AxisParameters::viscous)) viscous_std = e.standard_error;
    }
    const double n2 = *section.gear_ratio * *section.gear_ratio;
    derived.push_back({"d_g", run.params.viscous / n2, viscous_std / n2,
                       section.linear ? "N m s/rad at the gear input, b / n_g^2 (n_g in rad/m)"
                                      : "N m s/rad at the gear input, b / n_g^2"});
  }
  // Feed-forward gains in the log's units (docs/models.md#feed-forward): SysId
  // logs carry voltage and their own position unit.
  const bool with_inertia = section.inertia.value_or(0.0) > 0.0 ||
                            std::any_of(run.fit.estimates.begin(), run.fit.estimates.end(), [](const auto& e) {
                              return e.name == KeyOf(AxisParameterTable(), &AxisParameters::inertia);
                            });
  fitted.feedforward = CalcAxisFeedforward(run.params, run.fit, sysid ? "V" : (section.linear ? "N" : "N m"),
                                           sysid ? sysid_units.front() : (section.linear ? "m" : "rad"), with_inertia);
  outputs.parameter_file = FormatParameterFile(fitted, &outputs.fit, &outputs.provenance, derived);
  outputs.trace_csv = run.trace_csv;
  if (!options.output.plot.empty()) outputs.plot_panels = MakeFitPanels(run.series, run.labels);
  EmitFitOutputs(options.output, outputs);
  if (!options.output.quiet && !options.output.json) {
    std::FILE* summary = options.output.output.empty() ? stderr : stdout;
    for (const auto& line : run.summary) std::fprintf(summary, "%s\n", line.c_str());
  }
}

namespace {
AxisOptions axis_options;
const bool kRegistered = RegisterCommand({"drivetrain-fit", "", 20,
                                          [](CLI::App& parent) { return SetupAxisCommand(parent, axis_options); },
                                          [](const std::string& line) { RunAxisCommand(axis_options, line); }});
}  // namespace

}  // namespace driveid::cli
