// cdrive-fit validate: predict both motor torques of C-drive logs from a
// parameter file by inverse dynamics (28) and report how well they match
// (docs/models.md#validation).
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "common/cli_support.h"
#include "common/command_registry.h"
#include "common/log_input_options.h"
#include "common/validation_output.h"
#include "core/errors.h"
#include "logs/cdrive_log.h"
#include "params/parameter_file.h"
#include "models/missing_values.h"
#include "workflow/validation_run.h"

namespace driveid::cli {
namespace {

struct CDriveValidateOptions {
  std::string params;
  std::vector<std::string> logs;
  LogInputCli input;
  double window = 0.01;
  double min_rate = 0.5;
  double settle = 0.1;
  FitOutputOptions output;
};

CLI::App* SetupCDriveValidate(CLI::App& app, CDriveValidateOptions& options) {
  CLI::App* command = app.add_subcommand(
      "validate",
      "Predict both motor torques of C-drive logs from a parameter file (inverse dynamics, eq. 28) and report fit %, "
      "RMSE and residual autocorrelation per log and motor (docs/models.md#validation)");
  command->add_option("params", options.params, "parameter file with a complete cdrive section")->required();
  command->add_option("logs", options.logs, "C-drive logs (CSV, MAT; docs/formats.md#logs) with t, psi_L, psi_R, "
                                            "tau_L, tau_R (or i_L, i_R)")
      ->required();
  AddLogInputOptions(*command, options.input, "psi_L=encoder_left");
  command->add_option("--window", options.window, "half window of the zero-phase differentiator [s]")
      ->capture_default_str()
      ->check(FiniteAbove(0.0));
  command->add_option("--min-rate", options.min_rate, "compare samples whose motor rates exceed this [rad/s]")
      ->capture_default_str()
      ->check(FiniteAtLeast(0.0));
  command->add_option("--settle", options.settle, "also leave out this long around each reversal [s]")
      ->capture_default_str()
      ->check(FiniteAtLeast(0.0));
  AddValidationOutputOptions(*command, options.output);
  command->footer(
      "Example:\n  cdrive-fit validate data/cdrive_table1.yaml data/cdrive_slow_helical.csv --plot validation.png");
  return command;
}

void RunCDriveValidate(const CDriveValidateOptions& options, const std::string& command_line) {
  CheckFitOutputs(options.output, LogCommandInputs(options.logs, options.params, options.input));
  const ParameterFile file = ReadParameterFile(options.params);
  const CDriveSection* section = file.Find<CDriveSection>();
  if (section == nullptr) throw InputError(fmt::format("{}: no 'cdrive' section", options.params));
  RequireModelValues(CDriveParameterTable(), *section, options.params, "cdrive", "the prediction");
  FitProvenance provenance;
  const auto logs = LoadLogs<CDriveLog>(options.logs, options.input, options.output, provenance, CDriveLogColumns(),
                                        [&](CsvLog csv) {
                                          return MakeCDriveLog(std::move(csv), section->torque_constant.value_or(0.0));
                                        });
  CDriveFitOptions prediction;
  prediction.half_window = options.window;
  prediction.min_rate = options.min_rate;
  prediction.settle = options.settle;
  const ValidationRun run = RunCDriveValidation(logs, *section, options.params, prediction);
  EmitValidation(options.output, {"cdrive-fit", command_line, run.method, run.title, run.unit}, run.logs);
}

const bool kRegistered = RegisterCommand(Command<CDriveValidateOptions>(
    "cdrive-fit", "", 25, [](CLI::App& parent, CDriveValidateOptions& o) { return SetupCDriveValidate(parent, o); },
    [](const CDriveValidateOptions& o, const std::string& line) { RunCDriveValidate(o, line); }));

}  // namespace
}  // namespace driveid::cli
