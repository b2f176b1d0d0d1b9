#include "drivetrain_fit/robot_command.h"

#include <optional>

#include <fmt/format.h>

#include "common/command_registry.h"
#include "core/errors.h"
#include "logs/csv_log.h"
#include "params/parameter_file.h"
#include "params/robot_coupling_section.h"
#include "logs/serial_robot_log.h"
#include "system/sha256.h"
#include "robot_description/urdf_robot.h"
#include "workflow/serial_robot_description.h"
#include "workflow/robot_identification.h"
#include "workflow/serial_robot_identification.h"

namespace driveid::cli {

CLI::App* SetupRobotCommand(CLI::App& app, RobotOptions& options) {
  CLI::App* command = app.add_subcommand(
      "robot", "Base parameters, friction and armature of a serial robot from its URDF (--urdf; "
               "docs/models.md#serial-robot), or Theta, m_c, d_g of the planar robot (docs/models.md#planar-robot)");
  command->add_option("logs", options.logs,
                      "robot logs (CSV, MAT, bags; docs/formats.md#logs): with --urdf t and per joint q_<joint> (or "
                      "q1..qN), optionally qd_<joint>, and tau_<joint>; else t, theta1..3, i1..3")
      ->required();
  command->add_option("--urdf", options.urdf, "the serial robot's URDF (docs/formats.md#urdf)");
  command->add_option("--params", options.params,
                      "parameter file with a planar_robot section (without --urdf), or with --urdf a robot section: "
                      "the coupling of a wrist's drives (docs/models.md#coupled-drives)");
  command->add_option("--prior-weight", options.prior_weight,
                      "--urdf: weight of the URDF's inertials in the physically consistent fit, relative to one std "
                      "of the data (docs/models.md#physical-consistency)")
      ->capture_default_str()
      ->check(FiniteAbove(0.0));
  command
      ->add_option_function<std::vector<std::string>>(
          "--per-direction",
          [&options](const std::vector<std::string>& texts) {
            for (const std::string& text : texts) {
              for (auto& name : SplitNames(text, EmptyNames::kRefuse)) options.per_direction.push_back(std::move(name));
            }
          },
          "--urdf: joints (comma-separated, or all) whose viscous friction is fitted per direction, b+- = viscous +- "
          "viscous_asymmetry (Coulomb friction per direction is Coulomb and the offset; docs/models.md#serial-robot)")
      ->type_name("JOINTS");
  AddFreeOption(*command, options.free,
                FreeOptionHelp(PlanarRobotParameterTable(), "robot") +
                    "; with --urdf: base parameters by their lead's name (Izz_link1, viscous_joint2), 'bodies' or "
                    "'drives' (default all): the others are held at the URDF's inertials and <dynamics> "
                    "(docs/models.md#serial-robot-identification)");
  options.free_option = command->get_option("--free");
  AddLogInputOptions(*command, options.input, "theta1=#2");
  command->add_option("--window", options.window,
                      "half window of the zero-phase differentiator [s] (default 0.005 planar, 0.05 with --urdf)")
      ->check(FiniteAbove(0.0));
  AddFitOutputOptions(*command, options.output);
  command->footer(
      "Example:\n  drivetrain-fit robot data/robot_triangle.csv --params data/robot_start.yaml -o robot.yaml \\\n"
      "      --trace robot_currents.csv --plot fig7.png\n"
      "  drivetrain-fit robot arm_log.csv --urdf arm.urdf --col q1=#2 --col tau1=10*#14 ... -o arm.yaml");
  return command;
}

namespace {

void RunSerialRobot(const RobotOptions& options, const std::string& command_line) {
  std::vector<std::string> inputs = LogCommandInputs(options.logs, options.urdf, options.input);
  if (!options.params.empty()) inputs.push_back(options.params);
  CheckFitOutputs(options.output, inputs);
  const RobotToIdentify arm = ReadRobotToIdentify(options.urdf, options.params);
  const UrdfRobot& robot = arm.robot;
  const std::optional<RobotCouplingSection>& coupling = arm.coupling;
  const std::string& urdf_text = arm.urdf_text;
  FitOutputs outputs;
  outputs.provenance.command = command_line;
  outputs.provenance.version = DRIVEID_VERSION;
  outputs.provenance.model = "serial robot from a URDF, rigid bodies and drives, base parameters (docs/models.md#serial-robot)";
  LogInputCli input = options.input;
  input.selection.bag.every_joint = true;  // a bag's JointState topic by joint name, as ‹joint› all
  const auto logs = LoadLogs<SerialRobotLog>(options.logs, input, options.output, outputs.provenance,
                                             SerialRobotLogColumns(robot.robot),
                                             [&](CsvLog csv) { return MakeSerialRobotLog(robot.robot, std::move(csv)); });
  SerialRobotIdentificationOptions run_options;
  run_options.fit.half_window = options.window > 0.0 ? options.window : 0.05;
  run_options.window_from_logs = !(options.window > 0.0);
  run_options.prior_weight = options.prior_weight;
  run_options.viscous_per_direction = options.per_direction;
  if (options.free_option != nullptr && options.free_option->count() > 0) run_options.fit.free = options.free;
  SetProgress(run_options.fit.fit, options.output.verbose, options.output.max_seconds);
  run_options.trace = !options.output.trace.empty();
  const SerialRobotIdentification run =
      IdentifySerialRobot(robot, options.urdf, Sha256Hex(urdf_text), logs, run_options);
  ParameterFile file;
  file.Set(run.section);
  if (coupling) file.Set(*coupling);
  outputs.fit = run.result.fit;
  outputs.parameter_file = FormatParameterFile(file, &outputs.fit, &outputs.provenance);
  outputs.trace_csv = run.trace_csv;
  outputs.plot_panels = run.panels;
  if (!options.output.json) outputs.summary = run.summary;
  EmitFitOutputs(options.output, outputs);
}

}  // namespace

void RunRobotCommand(const RobotOptions& options, const std::string& command_line) {
  if (!options.urdf.empty()) return RunSerialRobot(options, command_line);
  if (!options.per_direction.empty()) throw OptionError("--per-direction: only with --urdf (a serial robot)");
  if (options.params.empty()) throw OptionError("robot: give --urdf (a serial robot) or --params (the planar robot)");
  CheckFitOutputs(options.output, LogCommandInputs(options.logs, options.params, options.input));
  const ParameterFile start = ReadParameterFile(options.params);
  if (!start.Find<PlanarRobotSection>()) throw InputError(fmt::format("{}: no 'planar_robot' section", options.params));
  FitOutputs outputs;
  outputs.provenance.command = command_line;
  outputs.provenance.version = DRIVEID_VERSION;
  outputs.provenance.model = "planar robot, rigid body (docs/models.md#planar-robot), projected with G";
  const auto logs = LoadLogs<RobotLog>(options.logs, options.input, options.output, outputs.provenance, RobotLogColumns(),
                                        [&](CsvLog csv) { return MakeRobotLog(std::move(csv)); });
  RobotIdentificationOptions run_options;
  run_options.fit.free = options.free;
  run_options.fit.half_window = options.window > 0.0 ? options.window : 0.005;
  SetProgress(run_options.fit.fit, options.output.verbose, options.output.max_seconds);
  run_options.trace = !options.output.trace.empty();
  const RobotIdentification run =
      IdentifyRobot(logs, MakePlanarRobotParameters(*start.Find<PlanarRobotSection>()), run_options);
  ParameterFile fitted = start;
  StoreModelParameters(PlanarRobotParameterTable(), run.params, *fitted.Find<PlanarRobotSection>());
  outputs.fit = run.fit;
  outputs.parameter_file = FormatParameterFile(fitted, &outputs.fit, &outputs.provenance);
  outputs.trace_csv = run.trace_csv;
  outputs.plot_panels = run.panels;
  EmitFitOutputs(options.output, outputs);
}

namespace {
const bool kRegistered = RegisterCommand(Command<RobotOptions>(
    "drivetrain-fit", "", 30, [](CLI::App& parent, RobotOptions& o) { return SetupRobotCommand(parent, o); },
    [](const RobotOptions& o, const std::string& line) { RunRobotCommand(o, line); }));
}  // namespace

}  // namespace driveid::cli
