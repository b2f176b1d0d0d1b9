#include "drivetrain_fit/validate_command.h"

#include <cstdio>

#include <fmt/format.h>

#include "common/command_registry.h"
#include "common/validation_output.h"
#include "core/errors.h"
#include "fit/axis_rows.h"
#include "fit/validation.h"
#include "io/axis_log.h"
#include "io/joint_log.h"
#include "io/parameter_file.h"
#include "io/step_log.h"
#include "models/missing_values.h"
#include "sim/mujoco_axis_simulator.h"

namespace driveid::cli {

CLI::App* SetupValidateCommand(CLI::App& app, ValidateOptions& options) {
  CLI::App* command = app.add_subcommand(
      "validate",
      "Predict logs from a parameter file (axis: inverse dynamics, or simulation with --simulate; step: simulation "
      "from the motor torque) or from an MJCF in MuJoCo, and report fit %, RMSE and residual autocorrelation per log "
      "(docs/models.md#validation, docs/export.md#validation-in-mujoco)");
  command->add_option("params", options.params,
                      "parameter file with an axis or drivetrain section, or an MJCF (.xml) as `export --to mjcf` "
                      "writes it, simulated in MuJoCo")
      ->required();
  command->add_option("logs", options.logs, "logs to predict (CSV, MAT, SysId JSON; docs/formats.md#logs)")->required();
  command->add_option("--model", options.model,
                      "axis or step (default: the parameter file's one model section); joint: an elastic joint's MJCF "
                      "driven by the motor torque")
      ->check(CLI::IsMember({"axis", "step", "joint"}));
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
  command->add_flag("--simulate", options.simulate,
                    "axis: simulate the position from the logged torque, Coulomb friction that sticks "
                    "(docs/models.md#axis-output-error), instead of the torque by inverse dynamics");
  command->add_option("--joint", options.joint,
                      "MJCF: the joint the logged effort drives (--model joint: the link joint; the motor is "
                      "JOINT_motor, as export names them)")
      ->capture_default_str();
  command->add_option("--mujoco-step", options.mujoco_step,
                      "MJCF: largest MuJoCo time step [s] (docs/export.md#validation-in-mujoco)")
      ->capture_default_str()
      ->check(FiniteAbove(0.0));
  AddValidationOutputOptions(*command, options.output);
  command->footer(
      "Example:\n  drivetrain-fit axis train.csv -o axis_fit.yaml\n"
      "  drivetrain-fit validate axis_fit.yaml held_out.csv --plot validation.png\n"
      "  drivetrain-fit export axis_fit.yaml --to mjcf -o axis.xml\n"
      "  drivetrain-fit validate axis.xml held_out.csv   # in MuJoCo; compare: validate axis_fit.yaml --simulate");
  return command;
}

namespace {

bool IsMjcf(const std::string& path) {
  const auto ends = [&](const std::string& suffix) {
    return path.size() >= suffix.size() && path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  return ends(".xml") || ends(".XML") || ends(".mjcf");
}

// An MJCF simulated in MuJoCo from the logged effort.
void RunMujocoValidation(const ValidateOptions& options, const std::string& command_line) {
  if (!options.model.empty() && options.model != "axis" && options.model != "joint") {
    throw OptionError(fmt::format("--model {}: an MJCF is validated as an axis or an elastic joint", options.model));
  }
  if (options.simulate) throw OptionError("--simulate: an MJCF is always simulated (in MuJoCo)");
  std::string why;
  if (!MujocoAvailable(&why)) throw InputError(fmt::format("{}: {}", options.params, why));
  FitProvenance provenance;
  provenance.command = command_line;
  if (options.model == "joint") {
    const auto logs = LoadLogs<JointLog>(options.logs, options.input, options.output, provenance, JointLogColumns(),
                                         [&](CsvLog csv) { return MakeJointLog(std::move(csv), 0.0); });
    EmitValidation(options.output,
                   {"drivetrain-fit", command_line,
                    fmt::format("MuJoCo simulation of the elastic joint '{}' (motor '{}_motor') from the logged motor "
                                "torque (held per sample, step <= {:g} s)",
                                options.joint, options.joint, options.mujoco_step),
                    "elastic joint in MuJoCo: motor and link angles simulated from the motor torque", "angle [rad]"},
                   ValidateMujocoJoint(logs, options.params, options.joint, options.mujoco_step));
    return;
  }
  const auto logs = LoadLogs<AxisLog>(options.logs, options.input, options.output, provenance, AxisLogColumns(),
                                      [&](CsvLog csv) { return MakeAxisLog(std::move(csv), 0.0); });
  MujocoAxisOptions mujoco;
  mujoco.joint = options.joint;
  mujoco.max_step = options.mujoco_step;
  const std::vector<ValidatedLog> validated = ValidateMujocoAxis(logs, options.params, mujoco);
  EmitValidation(options.output,
                 {"drivetrain-fit", command_line,
                  fmt::format("MuJoCo simulation of joint '{}' from the logged effort (held per sample, step <= {:g} s)",
                              options.joint, options.mujoco_step),
                  "axis validation in MuJoCo: position simulated from the logged effort", "position"},
                 validated);
}

}  // namespace

void RunValidateCommand(const ValidateOptions& options, const std::string& command_line) {
  CheckFitOutputs(options.output, LogCommandInputs(options.logs, options.params, options.input));
  if (IsMjcf(options.params)) {
    RunMujocoValidation(options, command_line);
    return;
  }
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
  if (model == "joint") {
    throw OptionError("--model joint: an elastic joint is validated from its MJCF in MuJoCo (drivetrain-fit export "
                      "P.yaml --to mjcf), not from a parameter file");
  }
  if (model == "axis" && axis == nullptr) throw InputError(fmt::format("{}: no 'axis' section", options.params));
  if (options.simulate && model != "axis") throw OptionError("--simulate: only an axis is simulated by validate --simulate (a drive train always is)");
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
    if (options.simulate) {
      validated = ValidateAxisBySimulation(logs, params);
      title = "axis validation: position simulated from the logged torque";
      unit = axis->linear ? "position [m]" : "position [rad]";
      method = "axis simulation from the logged torque (held per sample, Coulomb friction that sticks)";
    } else {
      const double cutoff =
          options.cutoff > 0.0 ? options.cutoff : ChooseAxisValidationCutoff(logs, params, options.decimation);
      validated = ValidateAxis(logs, params, cutoff, options.decimation);
      title = "axis validation: inverse dynamics (filtered, decimated)";
      unit = "force or torque";
      method = fmt::format("axis inverse dynamics, position cutoff {:.4g} Hz ({})", cutoff,
                           options.cutoff > 0.0 ? "given" : "the candidate that predicts best");
    }
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
