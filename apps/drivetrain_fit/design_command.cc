// drivetrain-fit design axis: the reference whose log the next fit needs
// (docs/models.md#excitation-design). Parsing and output only; the run is
// workflow/excitation_design.h.
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/cli_support.h"
#include "common/command_registry.h"
#include "core/errors.h"
#include "system/atomic_file.h"
#include "params/parameter_file.h"
#include "workflow/excitation_design.h"

namespace driveid::cli {
namespace {

struct DesignAxisOptions {
  std::string params, output, plot;
  std::vector<double> band;
  std::vector<std::string> targets;
  AxisDesignOptions design;
  bool json = false;
};

CLI::App* Setup(CLI::App& design, DesignAxisOptions& o) {
  CLI::App* c = design.add_subcommand(
      "axis", "A periodic position reference for the axis's position loop that minimises the next fit's std within "
              "the limits (docs/models.md#excitation-design)");
  AxisDesignOptions& d = o.design;
  c->add_option("--params", o.params, "prior: parameter file with an axis section (an axis fit's output)")->required();
  AddFreeOption(*c, d.free, "parameters the next fit estimates (default: inertia,viscous,coulomb,offset)");
  c->add_option("--duration", d.duration, "log length [s]")->required()->check(FiniteAbove(0.0));
  c->add_option("--rate", d.rate, "logging rate [Hz]")->capture_default_str()->check(FiniteAbove(0.0));
  c->add_option("--period", d.period,
                "reference period [s] (default: the best of the duration in 1, 2 and 4 x as many periods as "
                "periods of at most 10 s take)")
      ->check(FiniteAbove(0.0));
  c->add_option("--max-position", d.max_position, "|q| limit about the start [rad or m]")->required()->check(FiniteAbove(0.0));
  c->add_option("--max-speed", d.max_rate, "|qd| limit [rad/s or m/s]")->required()->check(FiniteAbove(0.0));
  c->add_option("--max-acceleration", d.max_acceleration, "|qdd| limit [rad/s^2 or m/s^2] (default: the torque's)")
      ->check(FiniteAbove(0.0));
  c->add_option("--max-torque", d.max_torque, "|tau| limit of the prior model [N m or N] (met to 95 %)")
      ->required()
      ->check(FiniteAbove(0.0));
  c->add_option("--band", o.band, "LO,HI: lines between [Hz] (default: the fundamental up to what the limits make "
                                  "worth exciting, below rate / 150)")
      ->delimiter(',')
      ->expected(2)
      ->check(FiniteAtLeast(0.0));
  c->add_option("--lines", d.lines, "at most this many lines in the band")->capture_default_str()->check(CLI::Range(2, 40));
  c->add_option("--criterion", d.criterion, "d: the geometric-mean std of the free parameters; a: the sum of the "
                                            "relative variances of --target")
      ->capture_default_str()
      ->check(CLI::IsMember({"d", "a"}));
  c->add_option("--target", o.targets, "a: the parameters that count (default: all free)")->delimiter(',');
  c->add_option("--noise", d.noise, "torque noise std per logged sample [N m or N] (default: from the prior's fit: "
                                    "its residual rmse x inflation x sqrt(10 / 0.8))")
      ->check(FiniteAbove(0.0));
  c->add_option("-o,--output", o.output, "reference CSV to write: t,q,qd,qdd (docs/formats.md#references; atomic)");
  c->add_flag("--json", o.json, "print one JSON object instead of the text");
  c->add_option("--plot", o.plot, "the reference over one period, the prior's torque and the lines (.png or .svg)")
      ->check(PlotPath());
  c->footer("Example:\n  drivetrain-fit axis first.csv -o prior.yaml\n"
            "  drivetrain-fit design axis --params prior.yaml --duration 20 --max-position 1 --max-speed 2 "
            "--max-torque 3 -o next.csv\n"
            "  drivetrain-fit simulate axis --params prior.yaml --reference next.csv -o try.csv");
  return c;
}

void Run(const DesignAxisOptions& o, const std::string& command_line) {
  CheckDistinctFiles({o.params}, {{"-o", o.output}, {"--plot", o.plot}});
  const ParameterFile file = ReadParameterFile(o.params);
  const ExcitationDesignRun run = DesignAxisRun(
      file, o.design, {o.params, o.band, o.targets, !o.output.empty(), !o.plot.empty(), o.json, command_line});
  std::vector<std::pair<std::string, std::string>> files;
  if (!o.output.empty()) files.emplace_back(o.output, run.csv);
  if (!o.plot.empty()) files.emplace_back(o.plot, RenderPanels(o.plot, run.panels, "time [s]"));
  // Standard output belongs to the transaction: a failed write changes no file.
  WriteFilesAtomically(files, [&] { WriteStdout(run.printed); });
}

const bool kGroup = RegisterGroup("drivetrain-fit", "design", 42,
                                  "Design the next experiment: excitation that minimises the fit's std within limits");
const bool kAxis = RegisterCommand(Command<DesignAxisOptions>(
    "drivetrain-fit", "design", 1, [](CLI::App& parent, DesignAxisOptions& o) { return Setup(parent, o); },
    [](const DesignAxisOptions& o, const std::string& line) { Run(o, line); }));

}  // namespace
}  // namespace driveid::cli
