// drivetrain-fit gains: feedback gains for the controller that loads the
// parameter file (docs/models.md#feedback-gains). Parsing and output only;
// the design is workflow/feedback_design.h.
#include <cstdio>
#include <functional>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "common/cli_support.h"
#include "common/command_registry.h"
#include "core/errors.h"
#include "system/atomic_file.h"
#include "params/parameter_file.h"
#include "workflow/feedback_design.h"

namespace driveid::cli {
namespace {

struct GainsOptions {
  std::string params;
  AxisGainsOptions axis;
  JointGainsOptions joint;
  double period = 0.0, delay = -1.0, kv = -1.0, ka = -1.0;
  std::string output, plot;
  bool json = false;
};

std::string PresetHelp() {
  std::string help = "controller conventions (units, period, velocity filter delay):";
  for (const auto& p : ControllerPresets()) help += fmt::format("\n  {}: {}", p.name, p.description);
  return help;
}

CLI::App* Setup(CLI::App& app, GainsOptions& o) {
  CLI::App* command = app.add_subcommand(
      "gains", "Feedback gains for a fitted axis by LQR as WPILib SysId computes them, with std from the fit "
      "(docs/models.md#feedback-gains)");
  command->add_option("params", o.params, "parameter file with a feedforward or axis section (an axis fit's output)");
  command->add_option("--loop", o.axis.loop,
                      "velocity: kp on the rate error; position: kp and kd (an axis); speed: a PI speed loop with a "
                      "notch at the resonance for an elastic joint (a joint section, docs/models.md#speed-loop)")
      ->capture_default_str()
      ->check(CLI::IsMember({"velocity", "position", "speed"}));
  command->add_option("--phase-margin", o.joint.phase_margin_deg, "speed loop: phase margin designed for [deg]")
      ->capture_default_str()
      ->check(FiniteWithin(1.0, 89.0));
  command->add_option("--notch-width", o.joint.notch_width_hz,
                      "speed loop: notch -3 dB width [Hz] (default: 30 % of the resonance or 4 std of it)")
      ->check(FiniteAbove(0.0));
  command->add_option("--preset", o.axis.preset, PresetHelp())->capture_default_str();
  command->add_option("--period", o.period, "controller period [s] (default: the preset's; speed loop 0.001)")->check(FiniteAbove(0.0));
  command->add_option("--delay", o.delay,
                      "velocity/position: the velocity measurement delay [s] (default: the preset's); speed: the "
                      "drive's delay from torque command to measured speed [s] (default: the file's fitted delay, "
                      "frf --free ...,delay), to which the loop adds 1.5 periods")
      ->check(FiniteAtLeast(0.0));
  command->add_option("--max-position-error", o.axis.max_position_error,
                      "LQR state cost: position error tolerated (default: as SysId: 0.1 on a fit in volts, as its GUI "
                      "sets it on loading data; else 1)")
      ->check(FiniteAbove(0.0));
  command->add_option("--max-velocity-error", o.axis.max_velocity_error,
                      "LQR state cost: velocity error tolerated (default: as SysId: (12 V - Ks) / (4 Kv) on a fit in "
                      "volts, as its GUI sets it on loading data; else 1.5)")
      ->check(FiniteAbove(0.0));
  command->add_option("--max-effort", o.axis.max_effort, "LQR effort cost: effort at those errors (V for SysId)")
      ->capture_default_str()
      ->check(FiniteAbove(0.0));
  command->add_option("--conversion", o.axis.conversion,
                      "controller position units per parameter-file position unit (e.g. encoder counts per rotation; "
                      "default: the preset's: rotations from an angle unit for ctre-phoenix6 and rev-*, 1 for wpilib; "
                      "ctre-phoenix5 needs it)")
      ->check(FiniteAbove(0.0));
  command->add_option("--kv", o.kv, "Kv [effort s/position] instead of the file's")->check(FiniteAtLeast(0.0));
  command->add_option("--ka", o.ka, "Ka [effort s^2/position] instead of the file's")->check(FiniteAtLeast(0.0));
  command->add_option("--kv-std", o.axis.kv_std, "std of a given Kv")->check(FiniteAtLeast(0.0));
  command->add_option("--ka-std", o.axis.ka_std, "std of a given Ka")->check(FiniteAtLeast(0.0));
  command->add_option("-o,--output", o.output,
                      "parameter file to write: the input's sections and the feedback section (written atomically)");
  command->add_flag("--json", o.json, "print one JSON object instead of the text");
  command->add_option("--plot", o.plot,
                      "speed loop: the open loop's Bode plot with its margins and the closed loop's step response "
                      "(.png or .svg)")
      ->check(PlotPath());
  command->footer(
      "Example:\n  drivetrain-fit axis sysid.json -o arm.yaml\n"
      "  drivetrain-fit gains arm.yaml --loop position --preset rev-neo -o arm_gains.yaml\n"
      "  drivetrain-fit gains --kv 3.060 --ka 0.327   (SysId's test: kp 2.11)");
  return command;
}

// -o (the input's sections and the feedback section) and --plot, all or
// nothing; then the design on standard output.
struct Emitted {
  const FeedbackController& controller;
  const std::vector<std::string>& notes;
  const std::vector<std::string>& warnings;
  std::function<std::vector<PlotPanel>()> panels;  // only with --plot
  Json json_extra = Json::object();
  std::string text_extra{};
};

void Emit(const GainsOptions& o, const std::optional<ParameterFile>& file, const Emitted& e) {
  std::vector<std::pair<std::string, std::string>> files;
  if (!o.output.empty()) {
    ParameterFile out = file ? *file : ParameterFile{};
    out.feedback = e.controller;
    files.emplace_back(o.output, FormatParameterFile(out));
  }
  if (!o.plot.empty()) files.emplace_back(o.plot, RenderPanels(o.plot, e.panels(), "frequency [Hz]", true));
  // Standard output belongs to the transaction: a failed write changes no file.
  WriteFilesAtomically(files, [&] {
    if (o.json) {
      Json json = FeedbackReportJson(e.controller);
      json.update(e.json_extra);
      json["notes"] = e.notes;
      json["warnings"] = e.warnings;
      WriteStdout(DumpJson(json));
    } else {
      std::string text = FormatFeedbackReport(e.controller) + e.text_extra;
      for (const auto& note : e.notes) text += "note: " + note + "\n";
      WriteStdout(text);
    }
  });
  for (const auto& warning : e.warnings) WriteText(stderr, "drivetrain-fit gains: warning: " + warning + "\n");
}

void RunSpeedLoop(const GainsOptions& o, const std::optional<ParameterFile>& file) {
  if (!file) throw OptionError("--loop speed needs a parameter file with a joint section");
  JointGainsOptions options = o.joint;
  if (o.period > 0.0) options.period = o.period;
  if (o.delay >= 0.0) options.delay = o.delay;
  const JointGainsDesign design = DesignJointGains(*file, o.params, options);
  Emit(o, file, {design.controller, design.notes, {}, [&] { return SpeedLoopPanels(design); }});
}

void Run(GainsOptions o) {
  CheckDistinctFiles({o.params}, {{"-o", o.output}, {"--plot", o.plot}});
  if (!o.plot.empty() && o.axis.loop != "speed") throw OptionError("--plot applies to --loop speed");
  std::optional<ParameterFile> file;
  if (!o.params.empty()) file = ReadParameterFile(o.params);
  if (o.period > 0.0) o.axis.period = o.period;
  if (o.delay >= 0.0) o.axis.delay = o.delay;
  if (o.kv >= 0.0) o.axis.kv = o.kv;
  if (o.ka >= 0.0) o.axis.ka = o.ka;
  if (o.axis.loop == "speed") return RunSpeedLoop(o, file);
  const AxisGainsDesign d = DesignAxisGains(file ? &*file : nullptr, o.params, o.axis);
  Emit(o, file, {d.controller, d.notes, d.warnings, {}, {{"plant", AxisGainsPlantJson(d)}}, FormatAxisGainsPlant(d)});
}

const bool kRegistered = RegisterCommand(Command<GainsOptions>(
    "drivetrain-fit", "", 45, [](CLI::App& parent, GainsOptions& o) { return Setup(parent, o); },
    [](const GainsOptions& o, const std::string&) { Run(o); }));
}  // namespace

}  // namespace driveid::cli
