// drivetrain-fit compare / cdrive-fit compare: parameter files against a
// base, with a drift gate for CI (docs/guide.md#fleets-and-drift). The
// comparison is lib/workflow/drift_comparison.h, its rendering
// lib/report/parameter_comparison.h.
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/cli_support.h"
#include "common/command_registry.h"
#include "core/errors.h"
#include "system/atomic_file.h"
#include "params/parameter_file.h"
#include "report/parameter_comparison.h"
#include "workflow/drift_comparison.h"

namespace driveid::cli {
namespace {

struct CompareOptions {
  std::string base;
  std::vector<std::string> files;
  std::optional<double> fail_above;
  std::optional<double> z;
  std::vector<std::string> parameters;
  bool json = false;
  std::string plot;
};

CLI::App* SetupCompare(CLI::App& parent, CompareOptions& o) {
  CLI::App* command = parent.add_subcommand(
      "compare",
      "Compare parameter files with a base: per estimate of the base's fit the relative change and z = change / "
      "sqrt(std^2 + std_base^2); exit 1 when a parameter drifts past --fail-above and/or --z (docs/guide.md#fleets-"
      "and-drift)");
  command->add_option("base", o.base, "the base parameter file (a fit's output: its fit.estimates)")->required();
  command->add_option("files", o.files, "parameter files to compare with it, in time order for --plot")->required();
  command->add_option("--fail-above", o.fail_above, "drift: |relative change| above PCT percent")
      ->type_name("PCT")
      ->check(FiniteAbove(0.0));
  command->add_option("--z", o.z, "drift: |z| above Z (with --fail-above: both)")->type_name("Z")->check(FiniteAbove(0.0));
  command->add_option_function<std::vector<std::string>>(
             "--parameters",
             [&o](const std::vector<std::string>& texts) {
               for (const auto& text : texts) {
                 for (auto& name : SplitNames(text, EmptyNames::kSkip)) o.parameters.push_back(std::move(name));
               }
             },
             "compare these estimates only (comma-separated; default: all of the base's)")
      ->type_name("NAMES");
  command->add_flag("--json", o.json, "print one JSON object (files[].file, .drift, .parameters.NAME.relative_change, .z)");
  command->add_option("--plot", o.plot, "plot each parameter's change across the files (.png or .svg)")
      ->check(PlotPath());
  command->footer(
      "Exit: 0 no drift, 1 a parameter drifted (after the report is printed), 2 usage, 3 an unreadable file.\n"
      "Example:\n  drivetrain-fit compare base.yaml fits/*.yaml --fail-above 10 --z 3 --json");
  return command;
}

void RunCompare(const CompareOptions& o) {
  std::vector<std::string> inputs = o.files;
  inputs.push_back(o.base);
  CheckDistinctFiles(inputs, {{"--plot", o.plot}});
  DriftGate gate;
  gate.max_percent = o.fail_above;
  gate.max_z = o.z;
  gate.parameters = o.parameters;
  const ParameterFile base = ReadParameterFile(o.base);
  if (base.fit_estimates.empty()) {
    throw InputError(fmt::format("{}: no fit.estimates: compare reads a fit's estimates and their std (a file that a "
                                 "fitting command wrote)",
                                 o.base));
  }
  std::vector<FileComparison> files;
  for (const auto& path : o.files) {
    const ParameterFile file = ReadParameterFile(path);
    if (file.fit_estimates.empty()) throw InputError(fmt::format("{}: no fit.estimates to compare", path));
    files.push_back(CompareEstimates(path, base.fit_estimates, file.fit_estimates, gate));
  }
  // Standard output belongs to the transaction: a failed write changes no file.
  std::vector<std::pair<std::string, std::string>> plot;
  if (!o.plot.empty()) {
    plot.emplace_back(o.plot, RenderPanels(o.plot, ComparisonPanels(files, gate), "file (in the order given)"));
  }
  WriteFilesAtomically(plot, [&] {
    WriteStdout(o.json ? DumpJson(ComparisonsJson(o.base, files, gate)) : FormatComparisons(o.base, files, gate));
  });
  const auto drifted = std::count_if(files.begin(), files.end(), [](const FileComparison& f) { return f.drift; });
  // One gate rule: a gate that cannot judge a file fails, naming why.
  std::vector<std::string> undecided;
  for (const auto& f : files) {
    for (const auto& u : f.undecided) undecided.push_back(fmt::format("{}: {}", f.file, u));
  }
  if (drifted > 0 || !undecided.empty()) {
    throw GateFailed{fmt::format("{} of {} files drifted from {}{}", drifted, files.size(), o.base,
                                 undecided.empty() ? std::string()
                                                   : fmt::format("; the gate cannot judge {}", fmt::join(undecided, "; ")))};
  }
}

const bool kDrivetrain = RegisterCommand(Command<CompareOptions>(
    "drivetrain-fit", "", 55, [](CLI::App& parent, CompareOptions& o) { return SetupCompare(parent, o); },
    [](const CompareOptions& o, const std::string&) { RunCompare(o); }));
const bool kCDrive = RegisterCommand(Command<CompareOptions>(
    "cdrive-fit", "", 55, [](CLI::App& parent, CompareOptions& o) { return SetupCompare(parent, o); },
    [](const CompareOptions& o, const std::string&) { RunCompare(o); }));

}  // namespace
}  // namespace driveid::cli
