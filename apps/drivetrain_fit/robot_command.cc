#include "drivetrain_fit/robot_command.h"

#include <fmt/format.h>

#include "common/command_registry.h"
#include "core/errors.h"
#include "io/csv_log.h"
#include "io/parameter_file.h"
#include "workflow/robot_identification.h"

namespace driveid::cli {

CLI::App* SetupRobotCommand(CLI::App& app, RobotOptions& options) {
  CLI::App* command = app.add_subcommand(
      "robot", "Theta, m_c, d_g of the planar robot from joint angles and motor currents (docs/models.md#planar-robot)");
  command->add_option("logs", options.logs, "robot logs (CSV, MAT; docs/formats.md#logs) with t, theta1..3, i1..3")->required();
  command->add_option("--params", options.params, "parameter file with a planar_robot section")->required();
  AddFreeOption(*command, options.free, FreeOptionHelp(PlanarRobotParameterTable(), "robot"));
  AddLogInputOptions(*command, options.input, "theta1=#2");
  command->add_option("--window", options.window, "half window of the zero-phase differentiator [s]")
      ->capture_default_str()
      ->check(FiniteAbove(0.0));
  AddFitOutputOptions(*command, options.output);
  command->footer(
      "Example:\n  drivetrain-fit robot data/robot_triangle.csv --params data/robot_start.yaml -o robot.yaml \\\n"
      "      --trace robot_currents.csv --plot fig7.png");
  return command;
}

void RunRobotCommand(const RobotOptions& options, const std::string& command_line) {
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
  run_options.fit.half_window = options.window;
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
RobotOptions robot_options;
const bool kRegistered = RegisterCommand({"drivetrain-fit", "", 30,
                                          [](CLI::App& parent) { return SetupRobotCommand(parent, robot_options); },
                                          [](const std::string& line) { RunRobotCommand(robot_options, line); }});
}  // namespace

}  // namespace driveid::cli
