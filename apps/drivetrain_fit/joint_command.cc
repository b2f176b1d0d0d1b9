#include "drivetrain_fit/joint_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <fmt/format.h>

#include "common/command_registry.h"
#include "core/errors.h"
#include "fit/joint_fit.h"
#include "io/csv_log.h"
#include "io/parameter_file.h"

namespace driveid::cli {

CLI::App* SetupJointCommand(CLI::App& app, JointOptions& options) {
  CLI::App* command = app.add_subcommand(
      "joint", "Elastic two-mass joint: motor and link inertia, stiffness, damping, friction by inverse dynamics "
               "(docs/models.md#elastic-joint)");
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
  command->add_option("--cutoff", options.cutoff, "angle low-pass cutoff [Hz] (default: rate / 40)")
      ->check(FiniteAbove(0.0));
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
  outputs.provenance.model = "elastic joint (docs/models.md#elastic-joint), inverse dynamics";
  const auto logs = LoadLogs<JointLog>(options.logs, options.input, options.output, outputs.provenance,
                                       JointLogColumns(), [&](CsvLog csv) {
                                         return MakeJointLog(std::move(csv), section.torque_constant.value_or(0.0));
                                       });
  JointFitOptions fit_options;
  fit_options.free = options.free;
  fit_options.cutoff = options.cutoff;
  SetProgress(fit_options.fit, options.output.verbose);
  const JointFitOutput result = FitJoint(logs, section, fit_options);

  ParameterFile fitted = start;
  JointSection out_section = section;
  StoreModelParameters(JointParameterTable(), result.params, out_section);
  fitted.Set(out_section);
  outputs.fit = result.fit;
  outputs.parameter_file = FormatParameterFile(fitted, &outputs.fit, &outputs.provenance);
  outputs.trace_csv = fmt::format("# drivetrain-fit joint trace: samples used (cutoff {} Hz); equation 0 motor, 1 total, "
                                  "2 shaft torque\n",
                                  result.cutoff);
  outputs.trace_csv += "log,equation,t,tau_measured,tau_model,residual\n";
  std::vector<PlotSeries> series(3 * logs.size());
  for (std::size_t i = 0; i < logs.size(); ++i) {
    series[3 * i].title = logs[i].path + " motor equation";
    series[3 * i + 1].title = logs[i].path + " total (motor + link)";
    series[3 * i + 2].title = logs[i].path + " shaft torque tau_link";
  }
  for (std::size_t k = 0; k < result.time.size(); ++k) {
    if (options.output.trace.empty() && options.output.plot.empty()) break;  // nothing asked for
    if (!options.output.trace.empty()) outputs.trace_csv += fmt::format("{},{},{},{:.7g},{:.7g},{:.7g}\n", result.log_index[k] + 1, result.equation[k],
                                     result.time[k], result.measured[k], result.model[k],
                                     result.measured[k] - result.model[k]);
    auto& s = series[static_cast<std::size_t>(3 * result.log_index[k] + result.equation[k])];
    s.time.push_back(result.time[k]);
    s.measured.push_back(result.measured[k]);
    s.model.push_back(result.model[k]);
  }
  series.erase(std::remove_if(series.begin(), series.end(), [](const PlotSeries& s) { return s.time.empty(); }),
               series.end());
  outputs.plot_panels = MakeFitPanels(series, {"elastic joint fit (link side)", "n tau, tau_link [N m]"});
  EmitFitOutputs(options.output, outputs);
  if (!options.output.quiet && !options.output.json) {
    std::FILE* summary = options.output.output.empty() ? stderr : stdout;
    const JointParameters& p = result.params;
    std::fprintf(summary, "angle cutoff %.4g Hz", result.cutoff);
    if (p.motor_inertia > 0.0 && p.link_inertia > 0.0 && p.stiffness > 0.0) {
      std::fprintf(summary, "; resonance sqrt(k (1/J_m + 1/J_l)) / (2 pi) = %.4g Hz",
                   std::sqrt(p.stiffness * (1.0 / p.motor_inertia + 1.0 / p.link_inertia)) / (2.0 * M_PI));
    }
    std::fprintf(summary, "\n");
  }
}

namespace {
JointOptions joint_options;
const bool kRegistered = RegisterCommand({"drivetrain-fit", "", 25,
                                          [](CLI::App& parent) { return SetupJointCommand(parent, joint_options); },
                                          [](const std::string& line) { RunJointCommand(joint_options, line); }});
}  // namespace

}  // namespace driveid::cli
