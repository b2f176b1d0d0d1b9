#include "drivetrain_fit/axis_command.h"

#include <algorithm>
#include <cstdio>

#include <fmt/format.h>

#include "common/command_registry.h"
#include "core/errors.h"
#include "fit/axis_fit.h"
#include "fit/validation.h"
#include "io/csv_log.h"
#include "io/parameter_file.h"
#include "io/sha256.h"
#include "report/axis_feedforward.h"

namespace driveid::cli {

CLI::App* SetupAxisCommand(CLI::App& app, AxisOptions& options) {
  CLI::App* command = app.add_subcommand(
      "axis", "Inertia, viscous and Coulomb friction and offset of a rigid axis by IDIM-LS (docs/models.md#axis)");
  command->add_option("logs", options.logs, "axis logs (CSV, MAT, SysId JSON; docs/formats.md#logs) with t, q and tau (or i with axis.k_t), optional qd")->required();
  command->add_option("--params", options.params, "parameter file with an axis section (start values, k_t, n_g)");
  AddFreeOption(*command, options.free, FreeOptionHelp(AxisParameterTable(), "axis"));
  AddLogInputOptions(*command, options.input, "q=pi/180*#2, tau=10*#14");
  command->add_option("--validate", options.validate,
                      "held-out logs (same columns) to predict with the fitted parameters: fit %, RMSE, lag-1 per log "
                      "(docs/models.md#validation)");
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

void RunAxisCommand(const AxisOptions& options, const std::string& command_line) {
  CheckFitOutputs(options.output, LogCommandInputs(options.logs, options.params, options.input, options.validate));
  ParameterFile start;
  if (!options.params.empty()) start = ReadParameterFile(options.params);
  const AxisSection section = start.Find<AxisSection>() ? *start.Find<AxisSection>() : AxisSection{};

  FitOutputs outputs;
  outputs.provenance.command = command_line;
  outputs.provenance.version = DRIVEID_VERSION;
  outputs.provenance.model = "axis (docs/models.md#axis), IDIM-LS";
  std::vector<std::string> sysid_units;  // per log: the SysId file's units, "" for other logs
  const auto logs = LoadLogs<AxisLog>(options.logs, options.input, options.output, outputs.provenance, AxisLogColumns(),
                                        [&](CsvLog csv) {
                                          sysid_units.push_back(csv.format == "sysid" ? csv.units : "");
                                          return MakeAxisLog(std::move(csv), section.torque_constant.value_or(0.0));
                                        });
  AxisFitOptions fit_options;
  fit_options.free = options.free;
  fit_options.cutoff = options.cutoff;
  fit_options.decimation = options.decimation;
  SetProgress(fit_options.fit, options.output.verbose);
  const AxisFitOutput result = FitAxis(logs, section, fit_options);

  ParameterFile fitted = start;
  AxisSection out_section = section;
  StoreModelParameters(AxisParameterTable(), result.params, out_section);
  fitted.Set(out_section);
  outputs.fit = result.fit;
  if (!options.validate.empty()) {
    FitProvenance held_out;
    const auto validation_logs = LoadLogs<AxisLog>(
        options.validate, options.input, options.output, held_out, AxisLogColumns(),
        [&](CsvLog csv) { return MakeAxisLog(std::move(csv), section.torque_constant.value_or(0.0)); });
    for (const auto& v : ValidateAxis(validation_logs, result.params, result.cutoff, options.decimation)) {
      outputs.fit.validation.push_back(v.stats);
    }
  }
  std::vector<DerivedQuantity> derived;
  derived.push_back({"relative_error_percent", result.relative_error_percent, 0.0, "% |tau - model| / |tau|"});
  if (section.gear_ratio) {
    double viscous_std = 0.0;
    for (const auto& e : result.fit.estimates) {
      if (e.name == KeyOf(AxisParameterTable(), &AxisParameters::viscous)) viscous_std = e.standard_error;
    }
    const double n2 = *section.gear_ratio * *section.gear_ratio;
    derived.push_back({"d_g", result.params.viscous / n2, viscous_std / n2, "N m s/rad at the gear input, b / n_g^2"});
  }
  // Feed-forward gains in the log's units (docs/models.md#feed-forward): SysId
  // logs carry voltage and their own position unit.
  const bool sysid = std::all_of(sysid_units.begin(), sysid_units.end(),
                                 [&](const std::string& u) { return !u.empty() && u == sysid_units.front(); });
  const bool with_inertia = section.inertia.value_or(0.0) > 0.0 ||
                            std::any_of(result.fit.estimates.begin(), result.fit.estimates.end(), [](const auto& e) {
                              return e.name == KeyOf(AxisParameterTable(), &AxisParameters::inertia);
                            });
  fitted.feedforward = CalcAxisFeedforward(result.params, result.fit, sysid ? "V" : "N m",
                                           sysid ? sysid_units.front() : "rad", with_inertia);
  outputs.parameter_file = FormatParameterFile(fitted, &outputs.fit, &outputs.provenance, derived);
  outputs.trace_csv = fmt::format("# drivetrain-fit axis trace: decimated samples used by IDIM-LS ({}, cutoff {} Hz)\n",
                                  result.method, result.cutoff);
  outputs.trace_csv += "log,t,tau_measured,tau_model,residual\n";
  std::vector<PlotSeries> series(logs.size());
  for (std::size_t i = 0; i < logs.size(); ++i) series[i].title = logs[i].path;
  for (std::size_t k = 0; k < result.time.size(); ++k) {
    const int i = result.log_index[k];
    outputs.trace_csv += fmt::format("{},{},{:.7g},{:.7g},{:.7g}\n", i + 1, result.time[k], result.measured[k],
                                     result.model[k], result.measured[k] - result.model[k]);
    auto& s = series[static_cast<std::size_t>(i)];
    s.time.push_back(result.time[k]);
    s.measured.push_back(result.measured[k]);
    s.model.push_back(result.model[k]);
  }
  outputs.plot_panels = MakeFitPanels(series, {"axis IDIM-LS fit (filtered, decimated)", "force or torque"});
  EmitFitOutputs(options.output, outputs);
  if (!options.output.quiet && !options.output.json) {
    std::FILE* summary = options.output.output.empty() ? stderr : stdout;
    std::fprintf(summary, "relative error of the fit %.2f %%, %d decimated samples, acceleration content %.3g 1/s\n",
                 result.relative_error_percent, result.samples_used, result.acceleration_content);
    std::fprintf(summary, "position cutoff %.4g Hz (%s)\n", result.cutoff, result.cutoff_rule.c_str());
  }
}

namespace {
AxisOptions axis_options;
const bool kRegistered = RegisterCommand({"drivetrain-fit", "", 20,
                                          [](CLI::App& parent) { return SetupAxisCommand(parent, axis_options); },
                                          [](const std::string& line) { RunAxisCommand(axis_options, line); }});
}  // namespace

}  // namespace driveid::cli
