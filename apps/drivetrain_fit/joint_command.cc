#include "drivetrain_fit/joint_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "common/command_registry.h"
#include "core/errors.h"
#include "fit/adequacy.h"
#include "fit/joint_fit.h"
#include "fit/joint_oe_fit.h"
#include "io/csv_log.h"
#include "io/parameter_file.h"
#include "report/fit_summary.h"

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
                      "have the motor torque and the inverse-dynamics filter reaches the resonance (cutoff < 2 x "
                      "resonance) or leaves the stiffness undetermined")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "id", "oe"}));
  command->add_option("--cutoff", options.cutoff, "angle low-pass cutoff [Hz] of --method id (default: rate / 40)")
      ->check(FiniteAbove(0.0));
  AddFitOutputOptions(*command, options.output);
  command->footer("Example:\n  drivetrain-fit joint data/joint_example.csv --params data/joint_start.yaml -o joint_fit.yaml "
                  "--plot joint_fit.png");
  return command;
}

namespace {

// What either method leaves for the outputs.
struct JointRun {
  JointParameters params;
  FitResult fit;
  std::string trace_csv;
  std::vector<PlotPanel> panels;
  std::vector<std::string> summary;  // lines for the text summary
};

JointRun RunInverseDynamics(const std::vector<JointLog>& logs, const JointSection& section, const JointOptions& options) {
  JointFitOptions fit_options;
  fit_options.free = options.free;
  fit_options.cutoff = options.cutoff;
  SetProgress(fit_options.fit, options.output.verbose);
  const JointFitOutput result = FitJoint(logs, section, fit_options);
  JointRun run{result.params, result.fit, {}, {}, {}};
  run.trace_csv = fmt::format("# drivetrain-fit joint trace: samples used (cutoff {} Hz); equation 0 motor, 1 total, "
                              "2 shaft torque\n",
                              result.cutoff);
  run.trace_csv += "log,equation,t,tau_measured,tau_model,residual\n";
  std::vector<PlotSeries> series(3 * logs.size());
  for (std::size_t i = 0; i < logs.size(); ++i) {
    series[3 * i].title = logs[i].path + " motor equation";
    series[3 * i + 1].title = logs[i].path + " total (motor + link)";
    series[3 * i + 2].title = logs[i].path + " shaft torque tau_link";
  }
  for (std::size_t k = 0; k < result.time.size(); ++k) {
    if (options.output.trace.empty() && options.output.plot.empty()) break;  // nothing asked for
    if (!options.output.trace.empty()) {
      run.trace_csv += fmt::format("{},{},{},{:.7g},{:.7g},{:.7g}\n", result.log_index[k] + 1, result.equation[k],
                                   result.time[k], result.measured[k], result.model[k],
                                   result.measured[k] - result.model[k]);
    }
    auto& s = series[static_cast<std::size_t>(3 * result.log_index[k] + result.equation[k])];
    s.time.push_back(result.time[k]);
    s.measured.push_back(result.measured[k]);
    s.model.push_back(result.model[k]);
  }
  series.erase(std::remove_if(series.begin(), series.end(), [](const PlotSeries& s) { return s.time.empty(); }),
               series.end());
  run.panels = MakeFitPanels(series, {"elastic joint fit (link side)", "n tau, tau_link [N m]"});
  run.summary.push_back(fmt::format("angle cutoff {:.4g} Hz", result.cutoff));
  return run;
}

JointRun RunOutputError(const std::vector<JointLog>& logs, const JointSection& section, const JointOptions& options,
                        const JointParameters* initial) {
  JointOeOptions oe_options;
  oe_options.free = options.free;
  SetProgress(oe_options.fit, options.output.verbose);
  const JointOeOutput result = FitJointOutputError(logs, section, initial, oe_options);
  JointRun run{result.params, result.fit, {}, {}, {}};
  const double n = *section.gear_ratio;
  run.trace_csv = "# drivetrain-fit joint trace: output error, simulated from the logged motor torque\n";
  run.trace_csv += "log,t,q_motor_measured,q_motor_model,q_link_measured,q_link_model\n";
  // The link angle, and the deflection q_motor / n - q_link that shows the spring.
  std::vector<PlotSeries> link, deflection;
  for (std::size_t i = 0; i < logs.size(); ++i) {
    const JointLog& log = logs[i];
    PlotSeries d{log.path + " deflection", log.time, {}, {}};
    for (std::size_t k = 0; k < log.time.size(); ++k) {
      d.measured.push_back(log.motor_position[k] / n - log.link_position[k]);
      d.model.push_back(result.motor_angle[i][k] / n - result.link_angle[i][k]);
      if (!options.output.trace.empty()) {
        run.trace_csv += fmt::format("{},{},{:.10g},{:.10g},{:.10g},{:.10g}\n", i + 1, log.time[k],
                                     log.motor_position[k], result.motor_angle[i][k], log.link_position[k],
                                     result.link_angle[i][k]);
      }
    }
    link.push_back({log.path + " q_link", log.time, log.link_position, result.link_angle[i]});
    run.summary.push_back(fmt::format("{}: simulated deflection q_motor/n - q_link fits {}", log.path,
                                      FitPercentText(result.deflection_fit_percent[i])));
    deflection.push_back(std::move(d));
  }
  if (!options.output.plot.empty()) {
    run.panels = MakeFitPanels(link, {"elastic joint, output error (simulated from the logged torque)", "q_link [rad]"});
    run.panels.resize(1);  // the link angle; its residuals show in the deflection's
    for (auto& panel : MakeFitPanels(deflection, {"deflection q_motor / n - q_link", "deflection [rad]"})) {
      run.panels.push_back(std::move(panel));
    }
  }
  return run;
}

// --method auto (docs/models.md#joint-output-error): output error when every
// log has the motor torque, the link's Coulomb friction is not asked for, and
// the inverse-dynamics start shows its filter reaching the resonance or leaves
// the stiffness undetermined. Returns the method and why.
std::pair<std::string, std::string> ChooseMethod(const std::vector<JointLog>& logs, const JointSection& section,
                                                 const JointOptions& options,
                                                 const std::optional<JointFitOutput>& start) {
  const bool torque = std::all_of(logs.begin(), logs.end(), [](const JointLog& l) { return !l.torque.empty(); });
  const std::string link_coulomb = KeyOf(JointParameterTable(), &JointParameters::link_coulomb);
  if (!torque) return {"id", "auto: a log has no motor torque to simulate from"};
  if (std::find(options.free.begin(), options.free.end(), link_coulomb) != options.free.end() ||
      section.link_coulomb.value_or(0.0) != 0.0) {
    return {"id", "auto: output error does not simulate the link's Coulomb friction"};
  }
  if (!start) return {"id", "auto: inverse dynamics, which output error starts from, refused the logs"};
  const JointParameters& p = start->params;
  for (const auto& e : start->fit.estimates) {
    if (e.name == link_coulomb && e.value > 3.0 * e.standard_error) {
      return {"id", fmt::format("auto: inverse dynamics finds link Coulomb friction {:.4g} +- {:.2g}, which output "
                                "error does not simulate",
                                e.value, e.standard_error)};
    }
  }
  for (const auto& e : start->fit.estimates) {
    if (e.name == KeyOf(JointParameterTable(), &JointParameters::stiffness) &&
        !(e.value > 0.0 && e.standard_error < kMaxRelativeStd * e.value)) {
      return {"oe", "auto: inverse dynamics leaves the stiffness undetermined"};
    }
  }
  if (p.motor_inertia > 0.0 && p.link_inertia > 0.0 && p.stiffness > 0.0) {
    const double resonance = JointResonance(p) / (2.0 * M_PI);
    if (start->cutoff < 2.0 * resonance) {
      return {"oe", fmt::format("auto: the inverse-dynamics cutoff {:.4g} Hz is below twice the resonance {:.4g} Hz",
                                start->cutoff, resonance)};
    }
    return {"id", fmt::format("auto: the inverse-dynamics cutoff {:.4g} Hz is above twice the resonance {:.4g} Hz",
                              start->cutoff, resonance)};
  }
  return {"oe", "auto: inverse dynamics gave no resonance"};
}

}  // namespace

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
  if (options.method == "oe") {
    if (options.cutoff > 0.0) throw OptionError("--cutoff applies to --method id only");
    CheckOutputErrorSimulates(section, options.free);
  }
  // Output error starts from inverse dynamics (its estimates however
  // uncertain); --method auto decides from it.
  std::optional<JointFitOutput> id_start;
  std::string method = options.method, why = "--method " + options.method;
  if (method != "id") {
    JointFitOptions id_options;
    id_options.free = options.free;
    id_options.cutoff = options.cutoff;
    id_options.per_log = id_options.sensitivity = id_options.refuse_undetermined = false;
    try {
      id_start = FitJoint(logs, section, id_options);
    } catch (const IdentificationError&) {
      // Inverse dynamics refused these logs: output error starts from the parameter file.
    }
  }
  if (method == "auto") std::tie(method, why) = ChooseMethod(logs, section, options, id_start);
  JointRun run = method == "oe" ? RunOutputError(logs, section, options, id_start ? &id_start->params : nullptr)
                                : RunInverseDynamics(logs, section, options);
  outputs.provenance.model = method == "oe" ? "elastic joint (docs/models.md#joint-output-error), output error "
                                              "(exact ZOH, sticking motor Coulomb)"
                                            : "elastic joint (docs/models.md#elastic-joint), inverse dynamics";
  run.summary.insert(run.summary.begin(),
                     fmt::format("method: {} ({})", method == "oe" ? "output error" : "inverse dynamics", why));
  if (method == "oe") {
    run.summary.push_back(id_start ? "start values from the inverse-dynamics fit" : "start values from --params");
  }

  ParameterFile fitted = start;
  JointSection out_section = section;
  StoreModelParameters(JointParameterTable(), run.params, out_section);
  fitted.Set(out_section);
  outputs.fit = run.fit;
  outputs.parameter_file = FormatParameterFile(fitted, &outputs.fit, &outputs.provenance);
  outputs.trace_csv = std::move(run.trace_csv);
  outputs.plot_panels = std::move(run.panels);
  EmitFitOutputs(options.output, outputs);
  if (!options.output.quiet && !options.output.json) {
    std::FILE* summary = options.output.output.empty() ? stderr : stdout;
    const JointParameters& p = run.params;
    for (const auto& line : run.summary) WriteText(summary, line + "\n");
    if (p.motor_inertia > 0.0 && p.link_inertia > 0.0 && p.stiffness > 0.0) {
      std::fprintf(summary, "resonance sqrt(k (1/J_m + 1/J_l)) / (2 pi) = %.4g Hz\n", JointResonance(p) / (2.0 * M_PI));
    }
  }
}

namespace {
JointOptions joint_options;
const bool kRegistered = RegisterCommand({"drivetrain-fit", "", 25,
                                          [](CLI::App& parent) { return SetupJointCommand(parent, joint_options); },
                                          [](const std::string& line) { RunJointCommand(joint_options, line); }});
}  // namespace

}  // namespace driveid::cli
