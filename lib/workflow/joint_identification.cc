#include "workflow/joint_identification.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"
#include "fit/core/adequacy.h"
#include "fit/joint/joint_fit.h"
#include "fit/joint/joint_mismatch.h"
#include "fit/joint/joint_oe_fit.h"
#include "report/fit_summary.h"

namespace driveid {

bool JointIdentificationOptions::IsValid(std::string* error) const {
  return OptionCheck(error)
      .Require(NotNegative(cutoff), "‹cutoff›", cutoff, "cutoff > 0 Hz (0: rate / 40)")
      .Require(segment_seconds >= 0.0, "‹segment›", segment_seconds, "segment >= 0 s (0: auto, inf: whole log)")
      .Nested(fit);
}
namespace {

// auto takes output error while the inverse-dynamics cutoff is below this
// many times the resonance: at 2.15 x (25 Hz on 11.6 Hz) inverse dynamics
// still missed J_m, b_m, c_m on 9-10 of 10 closed-loop seeds where output
// error covered them (tests/fit/joint_oe_coverage_test.cc).
constexpr double kAutoCutoffPerResonance = 4.0;

// What either method leaves for the outputs.
struct JointRun {
  JointParameters params;
  FitResult fit;
  std::string trace_csv;
  std::vector<PlotPanel> panels;
  std::vector<std::string> summary;  // lines for the text summary
};

JointRun RunInverseDynamics(const std::vector<JointLog>& logs, const JointSection& section,
                            const JointIdentificationOptions& options) {
  JointFitOptions fit_options;
  fit_options.free = options.free;
  fit_options.cutoff = options.cutoff;
  fit_options.fit = options.fit;
  const JointFitOutput result = FitJoint(logs, section, fit_options);
  JointRun run{result.params, result.fit, {}, {}, {}};
  if (options.trace) {
    run.trace_csv = fmt::format("# drivetrain-fit joint trace: samples used (cutoff {} Hz); equation 0 motor, 1 total, "
                                "2 shaft torque\n",
                                result.cutoff);
    run.trace_csv += "log,equation,t,tau_measured,tau_model,residual\n";
  }
  std::vector<PlotSeries> series(3 * logs.size());
  for (std::size_t i = 0; i < logs.size(); ++i) {
    series[3 * i].title = logs[i].path + " motor equation";
    series[3 * i + 1].title = logs[i].path + " total (motor + link)";
    series[3 * i + 2].title = logs[i].path + " shaft torque tau_link";
  }
  for (std::size_t k = 0; k < result.time.size(); ++k) {
    if (!options.trace && !options.plot) break;  // nothing asked for
    if (options.trace) {
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
  if (options.plot) run.panels = MakeFitPanels(series, {"elastic joint fit (link side)", "n tau, tau_link [N m]"});
  run.summary.push_back(fmt::format("angle cutoff {:.4g} Hz", result.cutoff));
  return run;
}

JointRun RunOutputError(const std::vector<JointLog>& logs, const JointSection& section,
                        const JointIdentificationOptions& options, const JointParameters* initial) {
  JointOeOptions oe_options;
  oe_options.free = options.free;
  oe_options.fit = options.fit;
  oe_options.segment_seconds = options.segment_seconds;
  const JointOeOutput result = FitJointOutputError(logs, section, initial, oe_options);
  JointRun run{result.params, result.fit, {}, {}, {}};
  const double n = *section.gear_ratio;
  if (options.trace) {
    run.trace_csv = "# drivetrain-fit joint trace: output error, simulated from the logged motor torque\n";
    run.trace_csv += "log,t,q_motor_measured,q_motor_model,q_link_measured,q_link_model\n";
  }
  // The link angle, and the deflection q_motor / n - q_link that shows the spring.
  std::vector<PlotSeries> link, deflection;
  for (std::size_t i = 0; i < logs.size(); ++i) {
    const JointLog& log = logs[i];
    PlotSeries d{log.path + " deflection", log.time, {}, {}};
    for (std::size_t k = 0; k < log.time.size(); ++k) {
      d.measured.push_back(log.motor_position[k] / n - log.link_position[k]);
      d.model.push_back(result.motor_angle[i][k] / n - result.link_angle[i][k]);
      if (options.trace) {
        run.trace_csv += fmt::format("{},{},{:.10g},{:.10g},{:.10g},{:.10g}\n", i + 1, log.time[k],
                                     log.motor_position[k], result.motor_angle[i][k], log.link_position[k],
                                     result.link_angle[i][k]);
      }
    }
    link.push_back({log.path + " q_link", log.time, log.link_position, result.link_angle[i]});
    run.summary.push_back(fmt::format("{}: deflection q_motor/n - q_link simulated over the whole log fits {}", log.path,
                                      FitPercentText(result.deflection_fit_percent[i])));
    deflection.push_back(std::move(d));
  }
  if (options.plot) {
    run.panels = MakeFitPanels(link, {"elastic joint, output error (simulated from the logged torque)", "q_link [rad]"});
    run.panels.resize(1);  // the link angle; its residuals show in the deflection's
    for (auto& panel : MakeFitPanels(deflection, {"deflection q_motor / n - q_link", "deflection [rad]"})) {
      run.panels.push_back(std::move(panel));
    }
  }
  return run;
}

// The link Coulomb friction an inverse-dynamics fit finds (more than 3 std).
std::optional<ParameterEstimate> FoundLinkCoulomb(const JointFitOutput& fit) {
  const std::string link_coulomb = KeyOf(JointParameterTable(), &JointParameters::link_coulomb);
  for (const auto& e : fit.fit.estimates) {
    if (e.name == link_coulomb && e.value > 3.0 * e.standard_error) return e;
  }
  return std::nullopt;
}

// The method auto takes, why, and whether the inverse-dynamics start had
// its filter near the resonance (what it finds is then suspect).
struct MethodChoice {
  JointMethod method;
  std::string why;
  bool filter_near_resonance = false;
};

// auto (docs/models.md#joint-output-error): output error when every log has
// the motor torque, the link's Coulomb friction is not asked for, and the
// inverse-dynamics start shows its filter near the resonance or — finding
// no link Coulomb friction — leaves a term undetermined (which inverse
// dynamics would refuse).
MethodChoice ChooseMethod(const std::vector<JointLog>& logs, const JointSection& section,
                          const JointIdentificationOptions& options, const std::optional<JointFitOutput>& start) {
  const bool torque = std::all_of(logs.begin(), logs.end(), [](const JointLog& l) { return !l.torque.empty(); });
  const std::string link_coulomb = KeyOf(JointParameterTable(), &JointParameters::link_coulomb);
  if (!torque) return {JointMethod::kInverseDynamics, "auto: a log has no motor torque to simulate from"};
  if (std::find(options.free.begin(), options.free.end(), link_coulomb) != options.free.end() ||
      section.link_coulomb.value_or(0.0) != 0.0) {
    return {JointMethod::kInverseDynamics, "auto: output error does not simulate the link's Coulomb friction"};
  }
  if (!start) return {JointMethod::kInverseDynamics, "auto: inverse dynamics, which output error starts from, refused the logs"};
  const JointParameters& p = start->params;
  const bool has_resonance = p.motor_inertia > 0.0 && p.link_inertia > 0.0 && p.stiffness > 0.0;
  const double resonance = has_resonance ? JointResonance(p) / (2.0 * M_PI) : 0.0;
  // With its filter near the resonance inverse dynamics is biased (the
  // damping most), and a link Coulomb friction it finds there may be the
  // filter's doing (a 4 kHz scope trace without any: 0.035 +- 0.006):
  // output error, warned of that friction.
  if (has_resonance && start->cutoff < kAutoCutoffPerResonance * resonance) {
    return {JointMethod::kOutputError,
            fmt::format("auto: the inverse-dynamics cutoff {:.4g} Hz is below 4 x the resonance {:.4g} Hz",
                        start->cutoff, resonance),
            true};
  }
  if (const auto found = FoundLinkCoulomb(*start)) {
    return {JointMethod::kInverseDynamics, fmt::format("auto: inverse dynamics finds link Coulomb friction {:.4g} +- "
                                                       "{:.2g}, which output error does not simulate",
                                                       found->value, found->standard_error)};
  }
  // A term inverse dynamics would refuse as undetermined (relative std above
  // 50 %, not at its bound 0): output error, which differentiates nothing.
  std::vector<std::string> undetermined;
  const std::string stiffness = KeyOf(JointParameterTable(), &JointParameters::stiffness);
  for (const auto& e : start->fit.estimates) {
    const bool at_bound = e.value == 0.0;
    if (!at_bound && !(e.standard_error < kMaxRelativeStd * std::abs(e.value))) undetermined.push_back(e.name);
    if (e.name == stiffness && !(e.value > 0.0)) {
      undetermined.push_back(e.name);
    }
  }
  if (!undetermined.empty()) {
    return {JointMethod::kOutputError,
            fmt::format("auto: inverse dynamics leaves {} undetermined", fmt::join(undetermined, ", "))};
  }
  if (has_resonance) {
    return {JointMethod::kInverseDynamics,
            fmt::format("auto: the inverse-dynamics cutoff {:.4g} Hz is above 4 x the resonance {:.4g} Hz",
                        start->cutoff, resonance)};
  }
  return {JointMethod::kOutputError, "auto: inverse dynamics gave no resonance"};
}

// Output error does not simulate the link's Coulomb friction; where the
// inverse-dynamics start finds it (more than 3 std), the fitted friction
// terms and inertias absorb it (the shipped example: b_m 16 %, c_m 50 %,
// b_l 30 % off, each outside its interval), and neither segments nor the
// deflection's fit show it.
void WarnLinkCoulomb(const JointFitOutput& start, bool filter_near_resonance, FitResult& fit) {
  if (const auto e = FoundLinkCoulomb(start)) {
    fit.warnings.push_back(fmt::format(
        "model: inverse dynamics finds link Coulomb friction {:.4g} +- {:.2g}{}, which output error does not simulate: "
        "{}the fitted friction terms and inertias absorb it; {} (docs/models.md#joint-output-error)",
        e->value, e->standard_error, filter_near_resonance ? " with its filter near the resonance" : "",
        filter_near_resonance ? "the filter's bias may have made it; if it is real, " : "",
        filter_near_resonance ? "check with ‹method› id at a ‹cutoff› of 4 x the resonance" : "use ‹method› id"));
  }
}

}  // namespace

JointIdentification IdentifyJoint(const std::vector<JointLog>& logs, const JointSection& section,
                                  const JointIdentificationOptions& options) {
  RequireValid(options);
  if (options.method == JointMethod::kOutputError) {
    if (options.cutoff > 0.0) throw OptionError("‹cutoff› applies to ‹method› id only");
  } else if (options.method == JointMethod::kInverseDynamics && options.segment_seconds != 0.0) {
    throw OptionError("‹segment› applies to ‹method› oe (or auto) only");
  }
  if (options.method == JointMethod::kOutputError) {
    CheckOutputErrorSimulates(section, options.free);
  }
  // Output error starts from inverse dynamics (its estimates however
  // uncertain); auto decides from it.
  std::optional<JointFitOutput> id_start;
  JointMethod method = options.method;
  std::string why = "asked for";
  if (method != JointMethod::kInverseDynamics) {
    JointFitOptions id_options;
    id_options.free = options.free;
    id_options.cutoff = options.cutoff;
    id_options.per_log = id_options.sensitivity = id_options.refuse_undetermined = false;
    id_options.mismatch = true;
    try {
      id_start = FitJoint(logs, section, id_options);
    } catch (const IdentificationError&) {
      // Inverse dynamics refused these logs: output error starts from the parameter file.
    }
  }
  bool filter_near_resonance = false;
  if (method == JointMethod::kAuto) {
    const MethodChoice choice = ChooseMethod(logs, section, options, id_start);
    method = choice.method;
    why = choice.why;
    filter_near_resonance = choice.filter_near_resonance;
  }
  const bool oe = method == JointMethod::kOutputError;
  JointRun run = oe ? RunOutputError(logs, section, options, id_start ? &id_start->params : nullptr)
                    : RunInverseDynamics(logs, section, options);
  if (oe && id_start) {
    WarnLinkCoulomb(*id_start, filter_near_resonance, run.fit);
    // What the model lacks, named from the inverse-dynamics rows (output
    // error simulates the same two-mass model and lacks it too).
    for (const auto& w : id_start->fit.warnings) {
      if (w.rfind(kJointMismatchPrefix, 0) == 0) run.fit.warnings.push_back(w);
    }
  }
  JointIdentification out;
  out.method = method;
  out.model = oe ? "elastic joint (docs/models.md#joint-output-error), output error (exact ZOH, sticking motor Coulomb)"
                 : "elastic joint (docs/models.md#elastic-joint), inverse dynamics";
  run.summary.insert(run.summary.begin(), fmt::format("method: {} ({})", oe ? "output error" : "inverse dynamics", why));
  if (oe) run.summary.push_back(id_start ? "start values from the inverse-dynamics fit" : "start values from ‹params›");
  if (!oe && options.segment_seconds != 0.0) run.summary.push_back("‹segment› unused: auto chose inverse dynamics");
  const JointParameters& p = run.params;
  if (p.motor_inertia > 0.0 && p.link_inertia > 0.0 && p.stiffness > 0.0) {
    run.summary.push_back(
        fmt::format("resonance sqrt(k (1/J_m + 1/J_l)) / (2 pi) = {:.4g} Hz", JointResonance(p) / (2.0 * M_PI)));
  }
  out.params = run.params;
  out.fit = std::move(run.fit);
  out.trace_csv = std::move(run.trace_csv);
  out.panels = std::move(run.panels);
  out.summary = std::move(run.summary);
  return out;
}

}  // namespace driveid
