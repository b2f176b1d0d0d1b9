#include "drivetrain_fit/validate_command.h"

#include <cstdio>

#include <fmt/format.h>

#include "common/command_registry.h"
#include "common/validation_output.h"
#include "core/errors.h"
#include "fit/axis_rows.h"
#include "fit/validation.h"
#include "io/axis_log.h"
#include "io/parameter_file.h"
#include "io/step_log.h"
#include "models/missing_values.h"

namespace driveid::cli {

CLI::App* SetupValidateCommand(CLI::App& app, ValidateOptions& options) {
  CLI::App* command = app.add_subcommand(
      "validate",
      "Predict logs from a parameter file (axis: inverse dynamics; step: simulation from the motor torque) and report "
      "fit %, RMSE and residual autocorrelation per log (docs/models.md#validation)");
  command->add_option("params", options.params, "parameter file with an axis or drivetrain section")->required();
  command->add_option("logs", options.logs, "logs to predict (CSV, MAT, SysId JSON; docs/formats.md#logs)")->required();
  command->add_option("--model", options.model, "axis or step (default: the parameter file's one model section)")
      ->check(CLI::IsMember({"axis", "step"}));
  command->add_option("--step-model", options.step_model, "step: reduced (eq. 16) or full (eqs. 13-14)")
      ->capture_default_str()
      ->check(CLI::IsMember({"reduced", "full"}));
  AddLogInputOptions(*command, options.input, "q=pi/180*#2, tau=10*#14");
  command->add_option("--cutoff", options.cutoff,
                      "axis: position low-pass cutoff [Hz] (default: the candidate that predicts best, "
                      "docs/models.md#axis-cutoff-from-the-data)")
      ->check(FiniteAbove(0.0));
  command->add_option("--decimation", options.decimation, "axis: parallel decimation factor")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  AddValidationOutputOptions(*command, options.output);
  command->footer(
      "Example:\n  drivetrain-fit axis train.csv -o axis_fit.yaml\n"
      "  drivetrain-fit validate axis_fit.yaml held_out.csv --plot validation.png");
  return command;
}

void RunValidateCommand(const ValidateOptions& options, const std::string& command_line) {
  CheckFitOutputs(options.output, LogCommandInputs(options.logs, options.params, options.input));
  const ParameterFile file = ReadParameterFile(options.params);
  const AxisSection* axis = file.Find<AxisSection>();
  const DriveTrainSection* drivetrain = file.Find<DriveTrainSection>();
  std::string model = options.model;
  if (model.empty()) {
    if (axis != nullptr && drivetrain != nullptr) {
      throw OptionError(fmt::format("{} has an axis and a drivetrain section: give --model axis or --model step",
                                    options.params));
    }
    model = axis != nullptr ? "axis" : "step";
  }
  if (model == "axis" && axis == nullptr) throw InputError(fmt::format("{}: no 'axis' section", options.params));
  if (model == "step" && drivetrain == nullptr) {
    throw InputError(fmt::format("{}: no 'drivetrain' section", options.params));
  }
  FitProvenance provenance;
  provenance.command = command_line;
  std::vector<ValidatedLog> validated;
  std::string title, unit, method;
  if (model == "axis") {
    RequireModelValues(AxisParameterTable(), *axis, options.params, "axis", "the prediction",
                       AxisTermsZeroUnlessGiven(*axis));
    const AxisParameters params = MakeModelParameters(AxisParameterTable(), *axis, AxisParameters{}, "axis");
    const auto logs = LoadLogs<AxisLog>(options.logs, options.input, options.output, provenance, AxisLogColumns(),
                                        [&](CsvLog csv) { return MakeAxisLog(std::move(csv), axis->torque_constant.value_or(0.0)); });
    const double cutoff =
        options.cutoff > 0.0 ? options.cutoff : ChooseAxisValidationCutoff(logs, params, options.decimation);
    validated = ValidateAxis(logs, params, cutoff, options.decimation);
    title = "axis validation: inverse dynamics (filtered, decimated)";
    unit = "force or torque";
    method = fmt::format("axis inverse dynamics, position cutoff {:.4g} Hz ({})", cutoff,
                         options.cutoff > 0.0 ? "given" : "the candidate that predicts best");
  } else {
    const DriveTrainParameters params = MakeDriveTrainParameters(*drivetrain);
    const auto logs = LoadLogs<StepLog>(options.logs, options.input, options.output, provenance, StepLogColumns(),
                                        [&](CsvLog csv) { return MakeStepLog(std::move(csv)); });
    validated = ValidateSteps(logs, params,
                              options.step_model == "full" ? DriveTrainModel::kFull : DriveTrainModel::kReduced);
    title = fmt::format("drive-train validation: simulation from the motor torque ({} model)", options.step_model);
    unit = "link torque [N m]";
    method = fmt::format("drive-train simulation ({} model) from tau_motor", options.step_model);
  }
  EmitValidation(options.output, {"drivetrain-fit", command_line, method, title, unit}, validated);
}

namespace {
ValidateOptions validate_options;
const bool kRegistered = RegisterCommand({"drivetrain-fit", "", 45,
                                          [](CLI::App& parent) { return SetupValidateCommand(parent, validate_options); },
                                          [](const std::string& line) { RunValidateCommand(validate_options, line); }});
}  // namespace

}  // namespace driveid::cli
