#include "drivetrain_fit/simulate_command.h"

#include <cstdio>

#include <fmt/format.h>

#include "common/cli_support.h"
#include "common/command_registry.h"
#include "system/atomic_file.h"
#include "params/parameter_file.h"

namespace driveid::cli {

CLI::App* SetupSimulateStepCommand(CLI::App& simulate, SimulateStepOptions& options) {
  CLI::App* step = simulate.add_subcommand(
      "step", "Motor-torque step with joint B fixed (default: the paper's -0.8 N m step, seed 000 Fig. 6)");
  step->add_option("--params", options.params, "parameter file with a drivetrain section")->required();
  step->add_option("-o,--output", options.output, "log file to write (default: stdout)");
  step->add_option("--model", options.model, "reduced or full")->check(CLI::IsMember({"reduced", "full"}));
  step->add_option("--rate", options.experiment.rate, "sampling rate [Hz]")->capture_default_str();
  step->add_option("--duration", options.experiment.duration, "log length [s]")->capture_default_str();
  step->add_option("--step-time", options.experiment.step_time, "time of the step [s]")->capture_default_str();
  step->add_option("--step-torque", options.experiment.step_torque, "motor torque after the step [N m]")
      ->capture_default_str();
  step->add_option("--noise", options.experiment.noise, "std of Gaussian noise on tau_link [N m]")->check(FiniteAtLeast(0.0))
      ->capture_default_str();
  step->add_option("--seed", options.experiment.seed, "noise seed")->check(Seed())->capture_default_str();
  step->add_option("--offset", options.experiment.offset, "constant strain-gauge bias [N m]")->capture_default_str();
  step->footer(
      "Example:\n"
      "  drivetrain-fit simulate step --params data/paper000.yaml --noise 0.1 --seed 1 -o step.csv");
  return step;
}

CLI::App* SetupSimulateAxisCommand(CLI::App& simulate, SimulateAxisOptions& axis_options) {
  CLI::App* axis = simulate.add_subcommand("axis", "Rigid axis following a prescribed motion (docs/models.md#axis)");
  AxisExperiment& e = axis_options.experiment;
  axis->add_option("--params", axis_options.params, "parameter file with an axis section")->required();
  axis->add_option("-o,--output", axis_options.output, "log file to write (default: stdout)");
  axis->add_option("--profile", e.profile, "multisine or constant")->capture_default_str();
  axis->add_option("--reference", axis_options.reference,
                   "follow this reference CSV (t,q[,qd,qdd], docs/formats.md#references; `design axis` writes one) "
                   "at its own times instead of a profile");
  axis->add_option("--rate", e.rate, "sampling rate [Hz]")->capture_default_str();
  axis->add_option("--duration", e.duration, "log length [s]")->capture_default_str();
  axis->add_option("--amplitude", e.amplitude, "multisine amplitude [rad or m]")->capture_default_str();
  axis->add_option("--speed", e.speed, "constant profile rate [rad/s or m/s]")->capture_default_str();
  axis->add_option("--resolution", e.resolution, "position quantum (0: none)")->capture_default_str();
  axis->add_option("--noise", e.noise, "std of force noise")->check(FiniteAtLeast(0.0))->capture_default_str();
  axis->add_option("--seed", e.seed, "noise seed")->check(Seed())->capture_default_str();
  axis->footer("Example:\n  drivetrain-fit simulate axis --params data/axis_example.yaml --noise 0.05 -o axis.csv");
  return axis;
}

CLI::App* SetupSimulateRobotCommand(CLI::App& simulate, SimulateRobotOptions& robot_options) {
  CLI::App* robot = simulate.add_subcommand(
      "robot", "Planar robot along the 250 mm triangle at 50 m/s^2 and 3 m/s (seed 000 section 6)");
  RobotExperiment& r = robot_options.experiment;
  robot->add_option("--params", robot_options.params, "parameter file with a planar_robot section")->required();
  robot->add_option("-o,--output", robot_options.output, "log file to write (default: stdout)");
  robot->add_option("--side", r.side, "triangle side [m]")->capture_default_str();
  robot->add_option("--acceleration", r.acceleration, "path acceleration [m/s^2]")->capture_default_str();
  robot->add_option("--speed", r.speed, "path speed [m/s]")->capture_default_str();
  robot->add_option("--dwell", r.dwell, "rest at each corner [s]")->capture_default_str();
  robot->add_option("--loops", r.loops, "loops around the triangle")->capture_default_str();
  robot->add_option("--rate", r.rate, "sampling rate [Hz]")->capture_default_str();
  robot->add_option("--prestress", r.prestress, "null-space joint torque at the gear output [N m]")
      ->capture_default_str();
  robot->add_option("--noise", r.current_noise, "std of current noise [A]")->check(FiniteAtLeast(0.0))->capture_default_str();
  robot->add_option("--seed", r.seed, "noise seed")->check(Seed())->capture_default_str();
  robot->footer("Example:\n  drivetrain-fit simulate robot --params data/robot_paper000.yaml --noise 0.02 -o triangle.csv");
  return robot;
}

void RunSimulateRobotCommand(const SimulateRobotOptions& options, const std::string& command_line) {
  CheckDistinctFiles({options.params}, {{"-o", options.output}});
  std::string text =
      SyntheticRobotLog(ReadParameterFile(options.params), options.params, options.experiment, command_line);
  if (options.output.empty()) {
    WriteStdout(text);
  } else {
    WriteFileAtomically(options.output, ShowFlags(std::move(text)));
  }
}

void RunSimulateAxisCommand(const SimulateAxisOptions& options, const std::string& command_line) {
  std::vector<std::string> inputs = {options.params};
  if (!options.reference.empty()) inputs.push_back(options.reference);
  CheckDistinctFiles(inputs, {{"-o", options.output}});
  std::string text = SyntheticAxisLog(ReadParameterFile(options.params), options.params, options.experiment,
                                      options.reference, command_line);
  if (options.output.empty()) {
    WriteStdout(text);
  } else {
    WriteFileAtomically(options.output, ShowFlags(std::move(text)));
  }
}

void RunSimulateStepCommand(const SimulateStepOptions& options, const std::string& command_line) {
  CheckDistinctFiles({options.params}, {{"-o", options.output}});
  std::string text = SyntheticStepLog(ReadParameterFile(options.params), options.params, options.model,
                                      options.experiment, command_line);
  if (options.output.empty()) {
    WriteStdout(text);
  } else {
    WriteFileAtomically(options.output, ShowFlags(std::move(text)));
  }
}

CLI::App* SetupSimulateJointCommand(CLI::App& simulate, SimulateJointOptions& o) {
  CLI::App* joint = simulate.add_subcommand(
      "joint", "Elastic joint under an excitation torque, open loop or injected after a PI speed loop: plan a "
               "frequency-response measurement (docs/models.md#frequency-response)");
  JointExperiment& e = o.experiment;
  joint->add_option("--params", o.params, "parameter file with a joint section (gear_ratio, inertias, stiffness, ...)")
      ->required();
  joint->add_option("-o,--output", o.output, "log file to write (default: stdout)");
  joint->add_option("--excitation", e.excitation, "multisine, chirp or prbs")->capture_default_str()
      ->check(CLI::IsMember({"multisine", "chirp", "prbs"}));
  joint->add_option("--band", o.band, "LO,HI: excited band [Hz]")->delimiter(',')->expected(2)
      ->check(FiniteAtLeast(0.0));
  joint->add_option("--amplitude", e.amplitude, "rms of the excitation torque [N m, motor shaft]")
      ->capture_default_str()->check(FiniteAtLeast(0.0));
  joint->add_option("--period", e.period, "multisine period, chirp sweep or PRBS sequence [s]")->capture_default_str()
      ->check(FiniteAbove(0.0));
  joint->add_option("--rate", e.rate, "sampling rate [Hz]")->capture_default_str()->check(FiniteWithin(1.0, 1e6));
  joint->add_option("--duration", e.duration, "log length [s] (with --reference: its length)")
      ->capture_default_str()
      ->check(FiniteAbove(0.0))
      ->each([&o](const std::string&) { o.duration_given = true; });
  joint->add_option("--reference", o.reference,
                    "inject this excitation CSV (t,tau at the logging rate, repeated; docs/formats.md#references; "
                    "`design joint` writes one) instead of --excitation, --band, --amplitude, --period, --rate");
  joint->add_option("--kp", e.kp, "PI speed loop: proportional gain [N m s/rad] (0: open loop)")->capture_default_str()
      ->check(FiniteWithin(-1e12, 1e12));
  joint->add_option("--ki", e.ki, "PI speed loop: integral gain [N m/rad]")->capture_default_str()
      ->check(FiniteWithin(-1e12, 1e12));
  joint->add_option("--noise", e.noise, "std of the motor-speed measurement noise [rad/s]")->capture_default_str()
      ->check(FiniteAtLeast(0.0));
  joint->add_option("--seed", e.seed, "noise seed")->check(Seed())->capture_default_str();
  joint->footer("Example:\n  drivetrain-fit simulate joint --params data/joint_example_truth.yaml --kp 0.0004 "
                "--ki 0.002 --noise 0.5 -o bench.csv\n  drivetrain-fit frf bench.csv --reference r --params "
                "data/joint_example_truth.yaml --fit two-mass --plot bode.png");
  return joint;
}

void RunSimulateJointCommand(const SimulateJointOptions& o, const std::string& command_line) {
  std::vector<std::string> inputs{o.params};
  if (!o.reference.empty()) inputs.push_back(o.reference);
  CheckDistinctFiles(inputs, {{"-o", o.output}});
  JointExperiment experiment = o.experiment;
  if (o.band.size() == 2) {
    experiment.f_low = o.band[0];
    experiment.f_high = o.band[1];
  }
  std::string text = SyntheticJointLog(ReadParameterFile(o.params), o.params, experiment, o.reference,
                                       o.duration_given, command_line);
  if (o.output.empty()) {
    WriteStdout(text);
  } else {
    WriteFileAtomically(o.output, ShowFlags(std::move(text)));
  }
}

namespace {
const bool kJoint = RegisterCommand(Command<SimulateJointOptions>(
    "drivetrain-fit", "simulate", 4, [](CLI::App& parent, SimulateJointOptions& o) { return SetupSimulateJointCommand(parent, o); },
    [](const SimulateJointOptions& o, const std::string& line) { RunSimulateJointCommand(o, line); }));
const bool kGroup = RegisterGroup("drivetrain-fit", "simulate", 40, "Write synthetic logs in the input format");
const bool kStep = RegisterCommand(Command<SimulateStepOptions>(
    "drivetrain-fit", "simulate", 1, [](CLI::App& parent, SimulateStepOptions& o) { return SetupSimulateStepCommand(parent, o); },
    [](const SimulateStepOptions& o, const std::string& line) { RunSimulateStepCommand(o, line); }));
const bool kAxis = RegisterCommand(Command<SimulateAxisOptions>(
    "drivetrain-fit", "simulate", 2, [](CLI::App& parent, SimulateAxisOptions& o) { return SetupSimulateAxisCommand(parent, o); },
    [](const SimulateAxisOptions& o, const std::string& line) { RunSimulateAxisCommand(o, line); }));
const bool kRobot = RegisterCommand(Command<SimulateRobotOptions>(
    "drivetrain-fit", "simulate", 3, [](CLI::App& parent, SimulateRobotOptions& o) { return SetupSimulateRobotCommand(parent, o); },
    [](const SimulateRobotOptions& o, const std::string& line) { RunSimulateRobotCommand(o, line); }));
}  // namespace

}  // namespace driveid::cli
