// drivetrain-fit design joint: the injected torque multisine whose log the
// next frequency-response fit needs (docs/models.md#joint-excitation-design).
// Parsing and output only; the run is workflow/excitation_design.h.
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

struct DesignJointOptions {
  std::string params, output, plot;
  std::vector<double> band;
  std::vector<std::string> targets;
  JointDesignOptions design;
  bool json = false;
};

CLI::App* Setup(CLI::App& design, DesignJointOptions& o) {
  CLI::App* c = design.add_subcommand(
      "joint", "An injected torque multisine whose line powers minimise the next frf two-mass fit's std within the "
               "torque and motor-speed limits (docs/models.md#joint-excitation-design)");
  JointDesignOptions& d = o.design;
  c->add_option("--params", o.params, "prior: parameter file with a joint section (gear_ratio, inertias, stiffness, "
                                      "damping; an frf fit's output)")
      ->required();
  AddFreeOption(*c, d.free, "parameters the next fit estimates (default: motor_inertia,link_inertia,stiffness,"
                            "damping,motor_viscous)");
  c->add_option("--duration", d.duration, "log length [s] (at least 5 periods)")->required()->check(FiniteAbove(0.0));
  c->add_option("--rate", d.rate, "logging rate [Hz]")->capture_default_str()->check(FiniteAbove(0.0));
  c->add_option("--period", d.period, "multisine period [s] (lines every 1/period Hz)")
      ->capture_default_str()
      ->check(FiniteAbove(0.0));
  c->add_option("--band", o.band, "LO,HI: lines between [Hz] (default: 0.5,50, as simulate joint's multisine)")
      ->delimiter(',')
      ->expected(2)
      ->check(FiniteAtLeast(0.0));
  c->add_option("--max-torque", d.max_torque, "|tau| limit of the injected torque [N m, log units]")
      ->required()
      ->check(FiniteAbove(0.0));
  c->add_option("--max-speed", d.max_speed, "|qd_motor| limit, the prior's steady response [rad/s, log units]")
      ->required()
      ->check(FiniteAbove(0.0));
  c->add_option("--noise", d.noise, "motor-speed noise std per sample [rad/s, log units]")
      ->required()
      ->check(FiniteAbove(0.0));
  c->add_option("--torque-noise", d.torque_noise, "noise std of the logged torque per sample [N m, log units]")
      ->capture_default_str()
      ->check(FiniteAtLeast(0.0));
  c->add_option("--criterion", d.criterion, "d: the geometric-mean std of the free parameters; a: the sum of the "
                                            "relative variances of --target")
      ->capture_default_str()
      ->check(CLI::IsMember({"d", "a"}));
  c->add_option("--target", o.targets, "the parameters that count (d: D_s-optimal, the other free ones nuisance; "
                                       "default: all free)")
      ->delimiter(',');
  c->add_option("--spread", d.spread, "share of the power spread evenly over the band (robustness to the prior)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 0.99));
  c->add_option("-o,--output", o.output, "excitation CSV to write: t,tau (docs/formats.md#references; atomic)");
  c->add_flag("--json", o.json, "print one JSON object instead of the text");
  c->add_option("--plot", o.plot, "both excitations over one period and their line amplitudes (.png or .svg)")
      ->check(PlotPath());
  c->footer("Example:\n  drivetrain-fit frf first.csv --params gear.yaml --fit two-mass -o prior.yaml\n"
            "  drivetrain-fit design joint --params prior.yaml --duration 20 --max-torque 2 --max-speed 5 "
            "--noise 0.02 -o next.csv\n"
            "  drivetrain-fit simulate joint --params prior.yaml --reference next.csv -o try.csv");
  return c;
}

void Run(const DesignJointOptions& o, const std::string& command_line) {
  CheckDistinctFiles({o.params}, {{"-o", o.output}, {"--plot", o.plot}});
  const ParameterFile file = ReadParameterFile(o.params);
  const ExcitationDesignRun run = DesignJointRun(
      file, o.design, {o.params, o.band, o.targets, !o.output.empty(), !o.plot.empty(), o.json, command_line});
  std::vector<std::pair<std::string, std::string>> files;
  if (!o.output.empty()) files.emplace_back(o.output, run.csv);
  if (!o.plot.empty()) files.emplace_back(o.plot, RenderPanels(o.plot, run.panels, "time [s]"));
  // Standard output belongs to the transaction: a failed write changes no file.
  WriteFilesAtomically(files, [&] { WriteStdout(run.printed); });
}

const bool kJoint = RegisterCommand(Command<DesignJointOptions>(
    "drivetrain-fit", "design", 2, [](CLI::App& parent, DesignJointOptions& o) { return Setup(parent, o); },
    [](const DesignJointOptions& o, const std::string& line) { Run(o, line); }));

}  // namespace
}  // namespace driveid::cli
