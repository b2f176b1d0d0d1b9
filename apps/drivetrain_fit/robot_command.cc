#include "drivetrain_fit/robot_command.h"

#include <fmt/format.h>

#include "common/command_registry.h"
#include "core/errors.h"
#include "fit/robot_fit.h"
#include "io/csv_log.h"
#include "io/parameter_file.h"
#include "io/sha256.h"

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
  RobotFitOptions fit_options;
  fit_options.free = options.free;
  fit_options.half_window = options.window;
  SetProgress(fit_options.fit, options.output.verbose, options.output.max_seconds);
  const RobotFitOutput result = FitRobot(logs, MakePlanarRobotParameters(*start.Find<PlanarRobotSection>()), fit_options);
  ParameterFile fitted = start;
  StoreModelParameters(PlanarRobotParameterTable(), result.params, *fitted.Find<PlanarRobotSection>());
  outputs.fit = result.fit;
  outputs.parameter_file = FormatParameterFile(fitted, &outputs.fit, &outputs.provenance);

  // Trace: the current prediction per motor, split as in seed 000 Fig. 7.
  outputs.trace_csv = "# motor currents [A]: measured, its motion (minimum-norm) part, and the model split into "
                      "inertia, centrifugal/Coriolis and friction (seed 000 Fig. 7)\n";
  outputs.trace_csv += "log,t,motor,i_measured,i_motion,i_model,i_inertia,i_coriolis,i_friction\n";
  for (std::size_t l = 0; l < result.predictions.size() && !options.output.trace.empty(); ++l) {
    const auto& p = result.predictions[l];
    for (std::size_t k = 0; k < p.time.size(); ++k) {
      for (std::size_t i = 0; i < 3; ++i) {
        outputs.trace_csv += fmt::format("{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}\n", l + 1, p.time[k], i + 1,
                                         p.measured[i][k], p.measured_motion[i][k], p.total[i][k], p.inertia[i][k],
                                         p.coriolis[i][k], p.friction[i][k]);
      }
    }
  }
  // Plot: motor 1 of the first log as in Fig. 7, then the residuals of all motors.
  const auto& first = result.predictions.front();
  PlotPanel figure{fmt::format("motor 1 current along {} (seed 000 Fig. 7)", logs.front().path), "current [A]",
                   {{"measured (motion part)", first.time, first.measured_motion[0], true},
                    {"model total", first.time, first.total[0], false},
                    {"inertia", first.time, first.inertia[0], false},
                    {"centrifugal/Coriolis", first.time, first.coriolis[0], false},
                    {"friction", first.time, first.friction[0], false}}};
  PlotPanel residual{"residual (measured motion part - model)", "current [A]", {}};
  for (std::size_t i = 0; i < 3; ++i) {
    std::vector<double> difference(first.time.size());
    for (std::size_t k = 0; k < difference.size(); ++k) difference[k] = first.measured_motion[i][k] - first.total[i][k];
    residual.lines.push_back({fmt::format("motor {}", i + 1), first.time, std::move(difference), false, true});
  }
  outputs.plot_panels = {figure, residual};
  EmitFitOutputs(options.output, outputs);
}

namespace {
RobotOptions robot_options;
const bool kRegistered = RegisterCommand({"drivetrain-fit", "", 30,
                                          [](CLI::App& parent) { return SetupRobotCommand(parent, robot_options); },
                                          [](const std::string& line) { RunRobotCommand(robot_options, line); }});
}  // namespace

}  // namespace driveid::cli
