#include "cdrive_fit/simulate_command.h"

#include <cstdio>

#include <fmt/format.h>

#include "common/cli_support.h"
#include "common/command_registry.h"
#include "system/atomic_file.h"
#include "params/parameter_file.h"
#include "report/json.h"
#include "report/plot.h"
#include "workflow/cdrive_simulation.h"

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
  CDriveSimulationRequest request;
  request.program = options.program;
  request.stroke = options.stroke;
  request.cycles = options.cycles;
  request.noise = options.noise;
  request.seed = options.seed;
  request.law = options.law;
  request.trace = !options.trace.empty();
  request.plot = !options.plot.empty();
  CDriveSimulation run = SimulateCDrive(ReadParameterFile(options.params), options.params, request, command_line);
  std::string& log_text = run.log_text;

  std::vector<std::pair<std::string, std::string>> files;  // written together, all or nothing
  if (!options.plot.empty()) files.emplace_back(options.plot, RenderPanels(options.plot, run.panels, "time [s]"));
  if (!options.trace.empty()) files.emplace_back(options.trace, std::move(run.trace_csv));
  if (!options.output.empty()) files.emplace_back(options.output, ShowFlags(std::move(log_text)));  // (not read again)
  const std::string summary = options.json ? DumpJson(run.summary_json) : run.summary;
  // Standard output belongs to the transaction (docs/formats.md#outputs).
  WriteFilesAtomically(files, [&] {
    if (options.output.empty()) WriteText(stderr, summary);
    WriteStdout(options.output.empty() ? log_text : summary);
  });
}

namespace {
const bool kRegistered = RegisterCommand(Command<CDriveSimulateOptions>(
    "cdrive-fit", "", 40, [](CLI::App& parent, CDriveSimulateOptions& o) { return SetupCDriveSimulateCommand(parent, o); },
    [](const CDriveSimulateOptions& o, const std::string& line) { RunCDriveSimulateCommand(o, line); }));
}  // namespace

}  // namespace driveid::cli
