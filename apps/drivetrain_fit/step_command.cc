#include "drivetrain_fit/step_command.h"

#include <fmt/format.h>

#include "common/command_registry.h"
#include "core/errors.h"
#include "logs/csv_log.h"
#include "params/parameter_file.h"
#include "workflow/step_identification.h"

namespace driveid::cli {

CLI::App* SetupStepCommand(CLI::App& app, StepOptions& options) {
  CLI::App* command = app.add_subcommand(
      "step", "Fit d_g, Theta_motor, tau_c (and more) to logged motor-torque step responses (docs/models.md#drive-train)");
  command->add_option("logs", options.logs, "step logs (CSV, MAT; docs/formats.md#logs) with t, tau_motor, tau_link; optional q_motor (motor encoder) "
                      "and q_link (gear output angle), which separate k_Tl and k_Tg (docs/models.md#drive-train)")->required();
  command->add_option("--params", options.params, "parameter file with known values and starting guesses")
      ->required();
  command->add_option("--model", options.model, "reduced (eq. 16, second order) or full (eqs. 13-14)")
      ->check(CLI::IsMember({"reduced", "full"}));
  command->add_option("--starts", options.starts,
                      "staged (from the fit of each log's first transient, read from the data), both (also from the "
                      "--params values; the lower cost wins, disagreement reported) or given (the --params values "
                      "only); docs/models.md#drive-train")
      ->check(CLI::IsMember({"staged", "both", "given"}));
  command->add_option("--integrator", options.integrator,
                      "exact (matrix exponentials per sample interval, the default) or cvodes (SUNDIALS CVODES, "
                      "restarted at each torque change: to cross-check); docs/models.md#drive-train")
      ->check(CLI::IsMember({"exact", "cvodes"}));
  AddFreeOption(*command, options.free, FreeOptionHelp(DriveTrainParameterTable(), "step", ", offset (a bias per log)"));
  AddLogInputOptions(*command, options.input, "tau_link=strain_gauge");
  command->add_option("--validate", options.validate,
                      "held-out logs (same columns) to simulate with the fitted parameters: fit %, RMSE, lag-1 per log "
                      "(docs/models.md#validation)");
  AddFitOutputOptions(*command, options.output);
  command->footer(
      "Example:\n"
      "  drivetrain-fit step data/fig6_step.csv --params data/paper000_start.yaml \\\n"
      "      --free d_g,Theta_motor,tau_c,offset -o fitted.yaml --plot fit.png --trace fit.csv");
  return command;
}

void RunStepCommand(const StepOptions& options, const std::string& command_line) {
  CheckFitOutputs(options.output, LogCommandInputs(options.logs, options.params, options.input, options.validate));
  const ParameterFile start_file = ReadParameterFile(options.params);
  if (!start_file.Find<DriveTrainSection>()) {
    throw InputError(fmt::format("{}: no 'drivetrain' section", options.params));
  }
  FitOutputs outputs;
  outputs.provenance.command = command_line;
  outputs.provenance.version = DRIVEID_VERSION;
  const auto make = [](CsvLog csv) { return MakeStepLog(std::move(csv)); };
  const auto logs =
      LoadLogs<StepLog>(options.logs, options.input, options.output, outputs.provenance, StepLogColumns(), make);
  std::vector<StepLog> validation;
  if (!options.validate.empty()) {
    FitProvenance held_out;
    validation = LoadLogs<StepLog>(options.validate, options.input, options.output, held_out, StepLogColumns(), make);
  }

  StepIdentificationOptions run_options;
  StepFitOptions& fit_options = run_options.fit;
  fit_options.model = options.model == "full" ? DriveTrainModel::kFull : DriveTrainModel::kReduced;
  fit_options.free = options.free;
  fit_options.starts = options.starts == "given" ? StepStarts::kGiven
                       : options.starts == "both" ? StepStarts::kBoth
                                                  : StepStarts::kStaged;
  fit_options.integration =
      options.integrator == "cvodes" ? DriveTrainIntegration::kCvodes : DriveTrainIntegration::kExact;
  SetProgress(fit_options.fit, options.output.verbose, options.output.max_seconds);
  run_options.trace = !options.output.trace.empty();
  run_options.plot = !options.output.plot.empty();
  const StepIdentification run =
      IdentifySteps(logs, MakeDriveTrainParameters(*start_file.Find<DriveTrainSection>()), run_options, validation);

  ParameterFile fitted = start_file;
  StoreModelParameters(DriveTrainParameterTable(), run.params, *fitted.Find<DriveTrainSection>());
  outputs.provenance.model = run.model;
  outputs.fit = run.fit;
  outputs.parameter_file = FormatParameterFile(fitted, &outputs.fit, &outputs.provenance);
  outputs.trace_csv = run.trace_csv;
  if (!options.output.plot.empty()) outputs.plot_panels = MakeFitPanels(run.series, run.labels);
  EmitFitOutputs(options.output, outputs);
}

namespace {
const bool kRegistered = RegisterCommand(Command<StepOptions>(
    "drivetrain-fit", "", 10, [](CLI::App& parent, StepOptions& o) { return SetupStepCommand(parent, o); },
    [](const StepOptions& o, const std::string& line) { RunStepCommand(o, line); }));
}  // namespace

}  // namespace driveid::cli
