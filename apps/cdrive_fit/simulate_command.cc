#include "cdrive_fit/simulate_command.h"

#include <cstdio>

#include <fmt/format.h>

#include "common/cli_support.h"
#include "common/command_registry.h"
#include "core/errors.h"
#include "io/atomic_file.h"
#include "io/parameter_file.h"
#include "models/missing_values.h"
#include "report/json.h"
#include "report/fit_summary.h"
#include "report/plot.h"
#include "sim/cdrive_closed_loop.h"

namespace driveid::cli {

CLI::App* SetupCDriveSimulateCommand(CLI::App& app, CDriveSimulateOptions& options) {
  CLI::App* command = app.add_subcommand(
      "simulate", "Closed-loop simulation of a Table II motion program at the controller rate (seed 001 IV.C-F)");
  command->add_option("--program", options.program, "translation, rotation or helical")
      ->required()
      ->check(CLI::IsMember({"translation", "rotation", "helical"}));
  command->add_option("--params", options.params, "parameter file with a cdrive section including control")->required();
  command->add_option("-o,--output", options.output, "log to write (default: stdout)");
  command->add_option("--stroke", options.stroke, "stroke time T [s]; one cycle is 2 T (seed: 1 s, 0.5 Hz)")
      ->capture_default_str();
  command->add_option("--cycles", options.cycles, "forward-and-back cycles")->capture_default_str();
  command->add_option("--noise", options.noise, "std of noise added to the logged torques [N m]")->check(FiniteAtLeast(0.0))->capture_default_str();
  command->add_option("--seed", options.seed, "noise seed")->check(Seed())->capture_default_str();
  command->add_option("--law", options.law, "override cdrive.control.law: PI, PD or PID")
      ->check(CLI::IsMember({"PI", "PD", "PID"}));
  command->add_option("--trace", options.trace, "CSV of the tracking errors in u [m] and theta [rad]");
  command->add_option("--plot", options.plot, "plot of the tracking errors (.png or .svg)")
      ->check(PlotPath());
  command->add_flag("--json", options.json, "print the summary as one JSON object");
  command->footer(
      "Example:\n  cdrive-fit simulate --program helical --params data/cdrive_table1.yaml --cycles 1 \\\n"
      "      -o helical.csv --trace helical_errors.csv --plot helical_errors.png");
  return command;
}

void RunCDriveSimulateCommand(const CDriveSimulateOptions& options, const std::string& command_line) {
  CheckDistinctFiles({options.params}, {{"-o", options.output}, {"--trace", options.trace}, {"--plot", options.plot}});
  const ParameterFile file = ReadParameterFile(options.params);
  if (!file.Find<CDriveSection>()) throw InputError(fmt::format("{}: no 'cdrive' section", options.params));
  RequireModelValues(CDriveParameterTable(), *file.Find<CDriveSection>(), options.params, "cdrive", "the simulation");
  const CDriveParameters params = MakeModelParameters(CDriveParameterTable(), *file.Find<CDriveSection>(), CDriveParameters{}, "cdrive");
  CDriveControlSettings settings = MakeControlSettings(file.Find<CDriveControlSection>() ? *file.Find<CDriveControlSection>() : CDriveControlSection{});
  if (options.law == "PI") settings.law = ControlLaw::kPI;
  if (options.law == "PD") settings.law = ControlLaw::kPD;
  if (options.law == "PID") settings.law = ControlLaw::kPID;

  ClosedLoopOptions loop;
  loop.program = TableTwoProgram(options.program, options.stroke);
  loop.cycles = options.cycles;
  loop.torque_noise = options.noise;
  loop.seed = options.seed;
  const ClosedLoopResult result = SimulateClosedLoop(params, settings, loop);

  const std::vector<std::string> comments = {
      "C-drive log (docs/formats.md#logs) made by: " + command_line,
      fmt::format("program {} (alpha_L {}, alpha_R {} rad), stroke {} s, {} cycles, {} at {} Hz, 13-bit encoders, "
                  "torque noise {} N m (seed {})",
                  loop.program.name, loop.program.amplitude_left, loop.program.amplitude_right, loop.program.stroke,
                  loop.cycles, ControlLawName(settings.law), 1.0 / settings.sample_time, options.noise, options.seed),
      fmt::format("truth: p {}, I_h {}, I_c {}, m {}, beta {}, gamma {}, delta {}, eta {}", params.lead,
                  params.hub_inertia, params.collar_inertia, params.collar_mass, params.viscous_motor,
                  params.viscous_collar, params.coulomb_motor, params.coulomb_collar)};
  std::string log_text = FormatCDriveLog(result.log, comments);

  std::vector<std::pair<std::string, std::string>> files;  // written together, all or nothing
  if (!options.plot.empty()) {
    std::vector<double> millimetres(result.tracking.translation_error);
    for (double& v : millimetres) v *= 1e3;
    files.emplace_back(options.plot, RenderPanels(options.plot,
                 {{fmt::format("tracking error in u, {} ({})", loop.program.name, ControlLawName(settings.law)),
                   "u error [mm]", {{"u_ref - u", result.tracking.time, millimetres, false}}},
                  {"tracking error in theta", "theta error [rad]",
                   {{"theta_ref - theta", result.tracking.time, result.tracking.rotation_error, false}}}},
                 "time [s]"));
  }
  if (!options.trace.empty()) {
    std::string trace = "# tracking errors from the encoder angles (docs/models.md#c-drive coordinates)\nt,u_error,theta_error\n";
    for (std::size_t k = 0; k < result.tracking.time.size(); ++k) {
      trace += fmt::format("{},{:.6g},{:.6g}\n", result.tracking.time[k], result.tracking.translation_error[k],
                           result.tracking.rotation_error[k]);
    }
    files.emplace_back(options.trace, std::move(trace));
  }
  if (!options.output.empty()) files.emplace_back(options.output, ShowFlags(std::move(log_text)));  // (not read again)
  std::string summary;
  if (options.json) {
    const Json json = {{"program", loop.program.name},
                       {"law", ControlLawName(settings.law)},
                       {"endpoint_u_error", result.endpoint_translation_error},
                       {"endpoint_theta_error", result.endpoint_rotation_error},
                       {"max_u_error", result.max_translation_error},
                       {"max_theta_error", result.max_rotation_error},
                       {"switches", result.switches}};
    summary = DumpJson(json);
  } else {
    summary = fmt::format(
                 "{}, {}: end-point error u {:.4f} mm, theta {:.5f} rad (seed 001: < 0.1 mm, < 0.01 rad); max over the "
                 "run u {:.3f} mm, theta {:.4f} rad; {} stick/slip switches\n",
                 loop.program.name, ControlLawName(settings.law), result.endpoint_translation_error * 1e3,
                 result.endpoint_rotation_error, result.max_translation_error * 1e3, result.max_rotation_error,
                 result.switches);
  }
  // Standard output belongs to the transaction (docs/formats.md#outputs).
  WriteFilesAtomically(files, [&] {
    if (options.output.empty()) WriteText(stderr, summary);
    WriteStdout(options.output.empty() ? log_text : summary);
  });
}

namespace {
CDriveSimulateOptions simulate_options;
const bool kRegistered = RegisterCommand(
    {"cdrive-fit", "", 40, [](CLI::App& parent) { return SetupCDriveSimulateCommand(parent, simulate_options); },
     [](const std::string& line) { RunCDriveSimulateCommand(simulate_options, line); }});
}  // namespace

}  // namespace driveid::cli
