#include "drivetrain_fit/validate_command.h"

#include <cstdio>
#include <optional>

#include <fmt/format.h>

#include "common/command_registry.h"
#include "common/validation_output.h"
#include "core/errors.h"
#include "logs/axis_log.h"
#include "logs/joint_log.h"
#include "params/parameter_file.h"
#include "params/robot_coupling_section.h"
#include "logs/step_log.h"
#include "logs/serial_robot_log.h"
#include "workflow/serial_robot_description.h"
#include "workflow/serial_robot_validation.h"
#include "workflow/validation_run.h"

namespace driveid::cli {

CLI::App* SetupValidateCommand(CLI::App& app, ValidateOptions& options) {
  CLI::App* command = app.add_subcommand(
      "validate",
      "Predict logs from a parameter file (axis: inverse dynamics, or simulation with --simulate; step: simulation "
      "from the motor torque) or from an MJCF in MuJoCo, and report fit %, RMSE and residual autocorrelation per log "
      "(docs/models.md#validation, docs/export.md#validation-in-mujoco)");
  command->add_option("params", options.params,
                      "parameter file with an axis, drivetrain or serial_robot section, or an MJCF (.xml) as `export --to mjcf` "
                      "writes it, simulated in MuJoCo")
      ->required();
  command->add_option("logs", options.logs, "logs to predict (CSV, MAT, SysId JSON; docs/formats.md#logs)")->required();
  command->add_option("--model", options.model,
                      "axis, step or robot (default: the parameter file's one model section); joint: an elastic "
                      "joint's MJCF driven by the motor torque; robot with an MJCF: every joint's torque by MuJoCo's "
                      "inverse dynamics")
      ->check(CLI::IsMember({"axis", "step", "joint", "robot"}));
  command->add_option("--urdf", options.urdf,
                      "robot: the URDF (default: the one the file's serial_robot section names; its SHA-256 must "
                      "match)");
  command->add_option("--step-model", options.step_model, "step: reduced (eq. 16) or full (eqs. 13-14)")
      ->capture_default_str()
      ->check(CLI::IsMember({"reduced", "full"}));
  // Before the log options: here --joint names the MJCF joint (a bag's joint is a --col).
  command->add_option("--joint", options.joint,
                      "MJCF: the joint the logged effort drives (--model joint: the link joint; the motor is "
                      "JOINT_motor, as export names them)")
      ->capture_default_str();
  AddLogInputOptions(*command, options.input, "q=pi/180*#2, tau=10*#14");
  command->add_option("--cutoff", options.cutoff,
                      "axis: position low-pass cutoff [Hz] (default: the candidate that predicts best, "
                      "docs/models.md#axis-cutoff-from-the-data)")
      ->check(FiniteAbove(0.0));
  command->add_option("--decimation", options.decimation,
                      "axis: parallel decimation factor (0: from the logs' rate and length, "
                      "docs/models.md#axis-decimation)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000));
  command->add_option("--torque-timing", options.torque_timing,
                      "axis: when the logged torque acts: file (the fit's reading, axis.torque_delay; sampled when "
                      "the file has none), sampled, held, or a delay in samples from -1 to 1 "
                      "(docs/models.md#torque-timing)")
      ->capture_default_str()
      ->check(TorqueTimingText(true));
  command->add_flag("--simulate", options.simulate,
                    "axis: simulate the position from the logged torque, Coulomb friction that sticks "
                    "(docs/models.md#axis-output-error), instead of the torque by inverse dynamics");
  command->add_option("--mujoco-step", options.mujoco_step,
                      "MJCF: largest MuJoCo time step [s] (docs/export.md#validation-in-mujoco)")
      ->capture_default_str()
      ->check(FiniteAbove(0.0));
  command->add_option("--window", options.window,
                      "robot from an MJCF: the differentiator's half window [s] (default 0.05, as robot --urdf; a "
                      "parameter file uses its own)")
      ->check(FiniteAbove(0.0));
  AddValidationOutputOptions(*command, options.output);
  command->footer(
      "Example:\n  drivetrain-fit axis train.csv -o axis_fit.yaml\n"
      "  drivetrain-fit validate axis_fit.yaml held_out.csv --plot validation.png\n"
      "  drivetrain-fit export axis_fit.yaml --to mjcf -o axis.xml\n"
      "  drivetrain-fit validate axis.xml held_out.csv   # in MuJoCo; compare: validate axis_fit.yaml --simulate\n"
      "  drivetrain-fit export arm.yaml --to mjcf -o arm.xml && drivetrain-fit validate arm.xml arm_log.csv --model robot");
  return command;
}

namespace {

bool IsMjcf(const std::string& path) {
  const auto ends = [&](const std::string& suffix) {
    return path.size() >= suffix.size() && path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  return ends(".xml") || ends(".XML") || ends(".mjcf");
}

}  // namespace

void RunValidateCommand(const ValidateOptions& options, const std::string& command_line) {
  CheckFitOutputs(options.output, LogCommandInputs(options.logs, options.params, options.input));
  const bool mjcf = IsMjcf(options.params);
  if (options.simulate && mjcf) throw OptionError("--simulate: an MJCF is always simulated (in MuJoCo)");
  std::optional<ParameterFile> file;
  if (!mjcf) file = ReadParameterFile(options.params);
  const ValidationModel model =
      ChooseValidationModel(file ? &*file : nullptr, mjcf, options.params, options.model);
  if (!options.urdf.empty() && mjcf) throw OptionError("--urdf: an MJCF holds its robot's structure itself");
  if (!options.urdf.empty() && model != ValidationModel::kSerialRobot) {
    throw OptionError("--urdf: only a serial robot's parameter file (serial_robot section) is validated with a URDF");
  }
  if (options.window > 0.0 && !(mjcf && model == ValidationModel::kSerialRobot)) {
    throw OptionError("--window: only a robot's MJCF is differentiated with it (a parameter file uses its own)");
  }
  if (options.simulate && model != ValidationModel::kAxis) {
    throw OptionError("--simulate: only an axis is simulated by validate --simulate (a drive train always is)");
  }
  FitProvenance provenance;
  provenance.command = command_line;
  // A serial robot's bag holds every joint by name (robot --urdf's
  // --joint all; validate's --joint is an MJCF's).
  LogInputCli input = options.input;
  input.selection.bag.every_joint = model == ValidationModel::kSerialRobot;
  const auto load = [&](const std::vector<std::string>& columns, auto make) {
    using Log = decltype(make(CsvLog{}));
    return LoadLogs<Log>(options.logs, input, options.output, provenance, columns, make);
  };
  ValidationRun run;
  if (mjcf && model == ValidationModel::kSerialRobot) {
    const SerialRobot robot = MjcfJoints(options.params);
    const auto logs =
        load(SerialRobotLogColumns(robot), [&](CsvLog csv) { return MakeSerialRobotLog(robot, std::move(csv)); });
    const double window = options.window > 0.0 ? options.window : DefaultSerialHalfWindow();
    run = RunMujocoSerialValidation(logs, options.params, robot, window);
  } else if (mjcf && model == ValidationModel::kJoint) {
    const auto logs = load(JointLogColumns(), [](CsvLog csv) { return MakeJointLog(std::move(csv), 0.0); });
    run = RunMujocoJointValidation(logs, options.params, options.joint, options.mujoco_step);
  } else if (mjcf) {
    const auto logs = load(AxisLogColumns(), [](CsvLog csv) { return MakeAxisLog(std::move(csv), 0.0); });
    run = RunMujocoValidation(logs, options.params, options.joint, options.mujoco_step);
  } else if (model == ValidationModel::kSerialRobot) {
    const SerialRobotSection& section = *file->Find<SerialRobotSection>();
    const SerialRobot robot = RobotOfParameterFile(*file, options.params, options.urdf);
    const auto logs =
        load(SerialRobotLogColumns(robot), [&](CsvLog csv) { return MakeSerialRobotLog(robot, std::move(csv)); });
    run = RunSerialRobotValidation(logs, section, robot, options.params);
  } else if (model == ValidationModel::kAxis) {
    const AxisSection& axis = *file->Find<AxisSection>();
    const double k_t = axis.torque_constant.value_or(0.0);
    const auto logs = load(AxisLogColumns(), [k_t](CsvLog csv) { return MakeAxisLog(std::move(csv), k_t); });
    AxisValidationOptions validation;
    validation.simulate = options.simulate;
    validation.cutoff = options.cutoff;
    validation.decimation = options.decimation;
    validation.timing_from_file = options.torque_timing == "file";
    if (!validation.timing_from_file) {
      validation.torque_timing = ParseAxisTorqueTiming(options.torque_timing, validation.torque_delay);
    }
    run = RunAxisValidation(logs, axis, options.params, validation);
  } else {
    const auto logs = load(StepLogColumns(), [](CsvLog csv) { return MakeStepLog(std::move(csv)); });
    run = RunStepValidation(logs, *file->Find<DriveTrainSection>(),
                            options.step_model == "full" ? DriveTrainModel::kFull : DriveTrainModel::kReduced);
  }
  EmitValidation(options.output, {"drivetrain-fit", command_line, run.method, run.title, run.unit}, run.logs);
}

namespace {
const bool kRegistered = RegisterCommand(Command<ValidateOptions>(
    "drivetrain-fit", "", 45, [](CLI::App& parent, ValidateOptions& o) { return SetupValidateCommand(parent, o); },
    [](const ValidateOptions& o, const std::string& line) { RunValidateCommand(o, line); }));
}  // namespace

}  // namespace driveid::cli
