// drivetrain-fit design robot: the Fourier trajectory per joint whose log the
// next robot --urdf fit needs (docs/models.md#serial-robot-excitation).
// Parsing and output only; the run is workflow/robot_excitation_design.h.
#include <optional>
#include <string>
#include <vector>

#include "common/cli_support.h"
#include "common/command_registry.h"
#include "core/errors.h"
#include "system/atomic_file.h"
#include "params/parameter_file.h"
#include "params/robot_coupling_section.h"
#include "params/serial_robot_section.h"
#include "robot_description/urdf_robot.h"
#include "workflow/serial_robot_description.h"
#include "workflow/robot_excitation_design.h"

namespace driveid::cli {
namespace {

struct DesignRobotOptions {
  std::string urdf, params, output, plot;
  std::vector<double> noise;
  RobotDesignOptions design;
};

CLI::App* Setup(CLI::App& design, DesignRobotOptions& o) {
  CLI::App* c = design.add_subcommand(
      "robot", "A periodic Fourier trajectory for every joint of a serial robot, starting and ending at rest, within "
               "its position, velocity and effort limits, that minimises the next robot --urdf fit's std of the base "
               "parameters (docs/models.md#serial-robot-excitation)");
  RobotDesignOptions& d = o.design;
  c->add_option("--urdf", o.urdf, "the robot's URDF (default: the one --params names; its SHA-256 must match)");
  c->add_option("--params", o.params,
                "prior: a robot --urdf fit (its consistent bodies, drives and per-joint residual noise); without it "
                "the URDF's inertials, no friction, and --noise");
  c->add_option("--duration", d.duration, "log length [s]")->required()->check(FiniteAbove(0.0));
  c->add_option("--rate", d.rate, "logging rate [Hz]")->capture_default_str()->check(FiniteAbove(0.0));
  c->add_option("--period", d.period, "trajectory period [s] (default: the duration in periods of at most 10 s)")
      ->check(FiniteAbove(0.0));
  c->add_option("--harmonics", d.harmonics, "lines per joint: harmonics 1..K of 1 / period")
      ->capture_default_str()
      ->check(CLI::Range(2, 20));
  c->add_option("--max-position", d.max_position, "|q - start| limit [rad or m] (default: the URDF's range only)")
      ->check(FiniteAbove(0.0));
  c->add_option("--max-speed", d.max_rate, "|qd| limit [rad/s or m/s] (default: each joint's URDF velocity limit)")
      ->check(FiniteAbove(0.0));
  c->add_option("--max-acceleration", d.max_acceleration, "|qdd| limit [rad/s^2 or m/s^2] (default: none)")
      ->check(FiniteAbove(0.0));
  c->add_option("--max-torque", d.max_torque,
                "|tau| limit of the prior model [N m or N] (default: each joint's URDF effort limit; met to 95 %)")
      ->check(FiniteAbove(0.0));
  c->add_option("--criterion", d.criterion,
                "d: the geometric-mean std of the base parameters; a: the sum of their relative variances")
      ->capture_default_str()
      ->check(CLI::IsMember({"d", "a"}));
  c->add_option("--noise", o.noise,
                "torque noise std per logged sample [N m or N]: one value, or one per joint (default: the prior "
                "fit's residual rmse x inflation per joint)")
      ->delimiter(',')
      ->check(FiniteAbove(0.0));
  c->add_option("--evaluations", d.evaluations, "of the optimiser per start (2 starts)")
      ->capture_default_str()
      ->check(CLI::Range(10, 1000000));
  c->add_option("-o,--output", o.output,
                "trajectory CSV to write: t, q_<joint>, qd_<joint>, qdd_<joint> (docs/formats.md#robot-trajectories; "
                "atomic)");
  c->add_option("--plot", o.plot, "every joint's trajectory (.png or .svg)")->check(PlotPath());
  c->footer("Example:\n  drivetrain-fit robot first.csv --urdf arm.urdf -o prior.yaml\n"
            "  drivetrain-fit design robot --params prior.yaml --duration 30 --rate 100 -o next.csv\n"
            "  drivetrain-fit design robot --urdf arm.urdf --noise 0.5 --duration 30 --max-speed 1 -o first.csv");
  return c;
}

void Run(const DesignRobotOptions& o, const std::string& command_line) {
  if (o.urdf.empty() && o.params.empty()) throw OptionError("give --urdf (the robot) or --params (a robot --urdf fit)");
  CheckDistinctFiles({o.params, o.urdf}, {{"-o", o.output}, {"--plot", o.plot}});
  std::optional<ParameterFile> file;
  SerialRobot robot;
  if (!o.params.empty()) {
    file = ReadParameterFile(o.params);
    if (const SerialRobotSection* section = file->Find<SerialRobotSection>()) {
      CheckDistinctFiles({section->urdf}, {{"-o", o.output}, {"--plot", o.plot}});
    }
    robot = RobotOfParameterFile(*file, o.params, o.urdf);
  } else {
    robot = ReadUrdfRobot(o.urdf).robot;
  }
  RobotDesignRequest request;
  request.prior = file ? &*file : nullptr;
  request.params_path = o.params;
  request.noise = o.noise;
  request.csv = !o.output.empty();
  request.plot = !o.plot.empty();
  request.command_line = command_line;
  const ExcitationDesignRun run = DesignRobotRun(robot, o.design, request);
  std::vector<std::pair<std::string, std::string>> files;
  if (!o.output.empty()) files.emplace_back(o.output, run.csv);
  if (!o.plot.empty()) files.emplace_back(o.plot, RenderPanels(o.plot, run.panels, "time [s]"));
  WriteFilesAtomically(files, [&] { WriteStdout(run.printed); });
}

const bool kRobot = RegisterCommand(Command<DesignRobotOptions>(
    "drivetrain-fit", "design", 3, [](CLI::App& parent, DesignRobotOptions& o) { return Setup(parent, o); },
    [](const DesignRobotOptions& o, const std::string& line) { Run(o, line); }));

}  // namespace
}  // namespace driveid::cli
