#include "drivetrain_fit/joint_command.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>

#include <fmt/format.h>

#include "common/command_registry.h"
#include "core/errors.h"
#include "logs/csv_log.h"
#include "params/parameter_file.h"
#include "workflow/joint_identification.h"

namespace driveid::cli {

CLI::App* SetupJointCommand(CLI::App& app, JointOptions& options) {
  CLI::App* command = app.add_subcommand(
      "joint", "Elastic two-mass joint: motor and link inertia, stiffness, damping, friction by inverse dynamics "
               "(docs/models.md#elastic-joint) or output error (docs/models.md#joint-output-error)");
  command->add_option("logs", options.logs,
                      "joint logs (CSV, MAT, SysId JSON; docs/formats.md#logs) with t, q_motor, q_link and tau (or i "
                      "with joint.k_t) or tau_link (a shaft-torque sensor) or both")
      ->required();
  command->add_option("--params", options.params, "parameter file with a joint section (gear_ratio; start and fixed values)")
      ->required();
  AddFreeOption(*command, options.free,
                FreeOptionHelp(JointParameterTable(), "joint") +
                    "; with tau_link also link_torque_offset, with tau_link only stiffness,damping,link_torque_offset");
  AddLogInputOptions(*command, options.input, "q_motor=#2, q_link=#3, tau=#4");
  command->add_option("--method", options.method,
                      "id: inverse dynamics (torques from the filtered, differentiated angles); oe: output error "
                      "(simulate from the logged motor torque with sticking motor Coulomb friction, fit q_motor, q_link, "
                      "rates and tau_link where logged; docs/models.md#joint-output-error); auto: oe when the logs "
                      "have the motor torque and the inverse-dynamics filter nears the resonance (cutoff < 4 x "
                      "resonance) or leaves a term undetermined (relative std above 50 %)")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "id", "oe"}));
  command->add_option("--cutoff", options.cutoff, "angle low-pass cutoff [Hz] of --method id (default: rate / 40)")
      ->check(FiniteAbove(0.0));
  command->add_option("--segment", options.segment,
                      "output error by multiple shooting: segment length [s], each segment simulated from its own "
                      "fitted initial state so that a measured torque's noise drifts over one segment only; auto: "
                      "4 periods of the start values' resonance, at most 24 segments a log, doubled while the fit is "
                      "refused; none: each log simulated whole "
                      "(docs/models.md#joint-output-error)")
      ->capture_default_str()
      ->check(CLI::Validator(
          [](const std::string& value) -> std::string {
            if (value == "auto" || value == "none") return "";
            char* end = nullptr;
            const double seconds = std::strtod(value.c_str(), &end);
            if (end != value.c_str() && *end == '\0' && std::isfinite(seconds) && seconds > 0.0) return "";
            return "expected auto, none or a number of seconds > 0, got '" + value + "'";
          },
          "auto|none|SECONDS", "segment"));
  options.output.max_seconds = 30.0;  // a joint output error on a long real log ends, at its best point
  AddFitOutputOptions(*command, options.output);
  command->footer("Example:\n  drivetrain-fit joint data/joint_example.csv --params data/joint_start.yaml -o joint_fit.yaml "
                  "--plot joint_fit.png");
  return command;
}

void RunJointCommand(const JointOptions& options, const std::string& command_line) {
  CheckFitOutputs(options.output, LogCommandInputs(options.logs, options.params, options.input, {}));
  ParameterFile start = ReadParameterFile(options.params);
  if (!start.Find<JointSection>()) throw InputError(fmt::format("{}: no 'joint' section", options.params));
  const JointSection section = *start.Find<JointSection>();

  FitOutputs outputs;
  outputs.provenance.command = command_line;
  outputs.provenance.version = DRIVEID_VERSION;
  const auto logs = LoadLogs<JointLog>(options.logs, options.input, options.output, outputs.provenance,
                                       JointLogColumns(), [&](CsvLog csv) {
                                         return MakeJointLog(std::move(csv), section.torque_constant.value_or(0.0));
                                       });
  JointIdentificationOptions run_options;
  run_options.method = options.method == "oe"   ? JointMethod::kOutputError
                       : options.method == "id" ? JointMethod::kInverseDynamics
                                                : JointMethod::kAuto;
  run_options.free = options.free;
  run_options.cutoff = options.cutoff;
  run_options.segment_seconds = options.segment == "auto"   ? 0.0
                                : options.segment == "none" ? HUGE_VAL
                                                            : std::strtod(options.segment.c_str(), nullptr);
  run_options.trace = !options.output.trace.empty();
  run_options.plot = !options.output.plot.empty();
  SetProgress(run_options.fit, options.output.verbose, options.output.max_seconds);
  JointIdentification run = IdentifyJoint(logs, section, run_options);

  ParameterFile fitted = start;
  JointSection out_section = section;
  StoreModelParameters(JointParameterTable(), run.params, out_section);
  fitted.Set(out_section);
  outputs.provenance.model = run.model;
  outputs.fit = run.fit;
  outputs.parameter_file = FormatParameterFile(fitted, &outputs.fit, &outputs.provenance);
  outputs.trace_csv = std::move(run.trace_csv);
  outputs.plot_panels = std::move(run.panels);
  EmitFitOutputs(options.output, outputs);
  if (!options.output.quiet && !options.output.json) {
    std::FILE* summary = options.output.output.empty() ? stderr : stdout;
    for (const auto& line : run.summary) WriteText(summary, line + "\n");
  }
}

namespace {
const bool kRegistered = RegisterCommand(Command<JointOptions>(
    "drivetrain-fit", "", 25, [](CLI::App& parent, JointOptions& o) { return SetupJointCommand(parent, o); },
    [](const JointOptions& o, const std::string& line) { RunJointCommand(o, line); }));
}  // namespace

}  // namespace driveid::cli
