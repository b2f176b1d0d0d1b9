#include "workflow/axis_identification.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <optional>

#include <fmt/format.h>

#include "core/clipped_text.h"
#include "core/errors.h"
#include "core/name_list.h"
#include "core/option_check.h"
#include "fit/axis/axis_adequacy.h"
#include "fit/axis/axis_fit.h"
#include "fit/core/adequacy.h"
#include "fit/axis/axis_oe_fit.h"
#include "fit/validation/validation.h"
#include "logs/column_expression.h"
#include "models/axis_term.h"
#include "models/feedforward.h"
#include "workflow/axis_feedforward.h"
#include "workflow/status_frame_logs.h"

namespace driveid {

bool AxisIdentificationOptions::IsValid(std::string* error) const {
  return OptionCheck(error).Nested(axis).Nested(axis.fit);
}
namespace {

void FitByInverseDynamics(const std::vector<AxisLog>& logs, const AxisIdentificationOptions& options,
                          const std::vector<AxisLog>& validation, AxisIdentification& run) {
  const AxisFitOutput result = FitAxis(logs, run.section, options.axis);
  // The reading, recorded for validate: as a delay in samples.
  run.section.torque_delay = result.torque_timing == AxisTorqueTiming::kDelayed ? result.torque_delay
                             : result.torque_timing == AxisTorqueTiming::kHeld  ? 0.5
                                                                                : 0.0;
  run.params = result.params;
  run.fit = result.fit;
  run.series.assign(logs.size(), {});
  run.labels = {"axis IDIM-LS fit (filtered, decimated)", "force or torque"};
  if (options.trace) {
    run.trace_csv = fmt::format("# drivetrain-fit axis trace: decimated samples used by IDIM-LS ({}, cutoff {} Hz)\n",
                                result.method, result.cutoff);
    run.trace_csv += "log,t,tau_measured,tau_model,residual\n";
  }
  for (std::size_t i = 0; i < logs.size(); ++i) run.series[i].title = logs[i].path;
  for (std::size_t k = 0; k < result.time.size(); ++k) {
    const int i = result.log_index[k];
    if (options.trace) {
      run.trace_csv += fmt::format("{},{},{:.7g},{:.7g},{:.7g}\n", i + 1, result.time[k], result.measured[k],
                                   result.model[k], result.measured[k] - result.model[k]);
    }
    auto& s = run.series[static_cast<std::size_t>(i)];
    s.time.push_back(result.time[k]);
    s.measured.push_back(result.measured[k]);
    s.model.push_back(result.model[k]);
  }
  for (const auto& v :
       ValidateAxis(validation, result.params, result.cutoff, result.decimation, result.torque_timing,
                    AxisReach::kAtCutoff, result.torque_delay)) {
    run.fit.validation.push_back(v.stats);
  }
  run.summary.push_back(fmt::format("processing: {}", result.method));
  run.summary.push_back(fmt::format("relative error of the fit {:.2f} %, {} decimated samples, acceleration content "
                                    "{:.3g} 1/s",
                                    result.relative_error_percent, result.samples_used, result.acceleration_content));
  run.summary.push_back(fmt::format("position cutoff {:.4g} Hz ({})", result.cutoff, result.cutoff_rule));
  run.summary.push_back(fmt::format("decimation {} ({})", result.decimation, result.decimation_rule));
  run.summary.push_back(fmt::format("torque timing {} ({})",
                                    DescribeAxisTorqueTiming(result.torque_timing, result.torque_delay),
                                    result.timing_rule));
  run.derived.push_back({"relative_error_percent", result.relative_error_percent, 0.0, "% |tau - model| / |tau|"});
  run.model = "axis (docs/models.md#axis), IDIM-LS";
}

// The output-error fit's start: inverse dynamics of the linear terms (the
// nonlinear ones are the output-error fit's) where it gives a usable inertia.
// Where inverse dynamics refuses the logs, the parameter file's values;
// without a start there, inverse dynamics' reason is rethrown.
std::optional<AxisParameters> OutputErrorStart(const std::vector<AxisLog>& logs, const AxisSection& section,
                                               const std::vector<std::string>& free) {
  std::optional<AxisParameters> initial;
  std::exception_ptr refused;
  try {
    AxisFitOptions idim;
    idim.free.clear();
    for (const auto& key : free) {
      if (AxisIndexOf(key) < AxisLinearCount()) idim.free.push_back(key);
    }
    idim.sensitivity = false;
    idim.per_log = false;
    idim.max_relative_std = 1e6;  // start values only: output error judges what the logs determine
    AxisSection linear = section;
    for (std::size_t j = AxisLinearCount(); j < AxisParameterCount(); ++j) SectionValue(AxisTermRow(j), linear).reset();
    const AxisFitOutput start = FitAxis(logs, linear, idim);
    if (start.params.inertia > 0.0) initial = start.params;
  } catch (const std::exception&) {
    refused = std::current_exception();
  }
  const bool inertia_free = Contains(free, AxisKey(&AxisParameters::inertia));
  if (!initial && refused && inertia_free && !(section.inertia.value_or(0.0) > 0.0)) std::rethrow_exception(refused);
  return initial;
}

// `measured`: the logs' measured rows for the start values; `logged`: the
// rows as logged, a second try for them (status frames too far apart for
// inverse dynamics to see the inertia still start it, lagged, above 0).
void FitByOutputError(const std::vector<AxisLog>& logs, const std::vector<AxisLog>& measured,
                      const std::vector<AxisLog>& logged, const AxisIdentificationOptions& options,
                      AxisIdentification& run) {
  std::optional<AxisParameters> initial;
  try {
    initial = OutputErrorStart(measured, run.section, options.axis.free);
  } catch (const IdentificationError&) {
    if (&logged == &measured) throw;
  }
  if (!initial && &logged != &measured) initial = OutputErrorStart(logged, run.section, options.axis.free);
  AxisOeOptions oe_options;
  oe_options.free = options.axis.free;
  oe_options.fit = options.axis.fit;
  const AxisOeOutput result = FitAxisOutputError(logs, run.section, initial ? &*initial : nullptr, oe_options);
  run.params = result.params;
  run.fit = result.fit;
  run.series.assign(logs.size(), {});
  run.labels = {"axis output-error fit (simulated from the logged torque)", "position"};
  if (options.trace) {
    run.trace_csv = "# drivetrain-fit axis trace: output error, simulated from the logged torque\n";
    run.trace_csv += "log,t,q_measured,q_model,qd_measured,qd_model\n";
  }
  for (std::size_t i = 0; i < logs.size(); ++i) {
    const AxisLog& log = logs[i];
    run.series[i] = {log.path, log.time, log.position, result.position[i]};
    for (std::size_t k = 0; k < log.time.size() && options.trace; ++k) {
      run.trace_csv += fmt::format("{},{},{:.10g},{:.10g},{},{:.7g}\n", i + 1, log.time[k], log.position[k],
                                   result.position[i][k], log.rate.empty() ? "" : fmt::format("{:.7g}", log.rate[k]),
                                   result.rate[i][k]);
    }
  }
  run.summary.push_back(fmt::format("start values from {}", result.start_from));
  std::vector<std::string> integrated;  // the terms the exact solution does not hold
  for (const AxisTerm* term : AxisTerms()) {
    if (!term->mode_affine()) integrated.push_back(term->name());
  }
  run.model = fmt::format("axis (docs/models.md#axis-output-error), output error (exact per held sample, CVODES with "
                          "{}; sticking Coulomb)",
                          JoinAsList(integrated, " or "));
}

// Units in the logs' units (SysId: volts and the file's unit; else rotary
// or linear SI), d_g = b / n_g^2 with a gear ratio, and the feed-forward.
void Interpret(const AxisIdentificationOptions& options, AxisIdentification& run) {
  const bool sysid = !options.sysid_unit.empty();
  const bool linear = run.section.linear;
  for (auto& e : run.fit.estimates) {
    if (const auto* row = FindParameter(AxisParameterTable(), e.name)) {
      e.unit = sysid ? AxisUnitIn(row->spec, "V", options.sysid_unit) : AxisUnit(row->spec, linear);
    }
  }
  if (run.section.gear_ratio) {
    double viscous_std = 0.0;
    for (const auto& e : run.fit.estimates) {
      if (e.name == AxisKey(&AxisParameters::viscous)) viscous_std = e.standard_error;
    }
    const double n2 = *run.section.gear_ratio * *run.section.gear_ratio;
    run.derived.push_back({"d_g", run.params.viscous / n2, viscous_std / n2,
                           linear ? "N m s/rad at the gear input, b / n_g^2 (n_g in rad/m)"
                                  : "N m s/rad at the gear input, b / n_g^2"});
  }
  const bool with_inertia = run.section.inertia.value_or(0.0) > 0.0 ||
                            std::any_of(run.fit.estimates.begin(), run.fit.estimates.end(), [](const auto& e) {
                              return e.name == AxisKey(&AxisParameters::inertia);
                            });
  run.feedforward = CalcAxisFeedforward(run.params, run.fit, sysid ? "V" : (linear ? "N" : "N m"),
                                        sysid ? options.sysid_unit : (linear ? "m" : "rad"), with_inertia);
  for (const char* mechanism : {"Simple", "Elevator", "Arm"}) {
    if (sysid && options.sysid_mechanism == mechanism) {
      run.feedforward.mechanism = options.sysid_mechanism == "Simple" ? "simple" : options.sysid_mechanism == "Elevator" ? "elevator" : "arm";
    }
  }
}

// SysId's test type says which gravity the mechanism carries: an Arm's
// Kg cos(q - angle) is fitted with the default free set (q in radians); an
// Elevator's constant Kg is the offset, free by default. Returns the note.
std::string MechanismFreeSet(const AxisIdentificationOptions& options, const AxisSection& section,
                             std::vector<std::string>& free) {
  if (options.sysid_mechanism == "Elevator") {
    return "SysId Elevator test: the constant gravity Kg is the offset (docs/models.md#feed-forward)";
  }
  if (options.sysid_mechanism != "Arm" || free != FitParameterKeys(AxisParameterTable(), "axis", true)) return "";
  if (section.linear || options.sysid_unit != "Radians") {
    throw OptionError(fmt::format("a SysId Arm test in '{}': the gravity term cos q needs the angle in Radians; "
                                  "record it so, or give ‹free› without gravity_cos, gravity_sin",
                                  options.sysid_unit));
  }
  for (const std::string& key : {AxisKey(&AxisParameters::gravity_cos), AxisKey(&AxisParameters::gravity_sin)}) {
    if (!Contains(free, key)) free.push_back(key);
  }
  return "SysId Arm test: gravity Kg cos(q - Kg_angle) fitted (gravity_cos, gravity_sin added to the default free set)";
}

// Where inverse dynamics warns that an estimate moves with the cutoff and
// advises output error (which does not differentiate), the advice is tried
// first: the warning says what output error gives for that parameter, and
// whether the two methods agree within 2 combined std (docs/models.md#adequacy).
void TryOutputErrorAdvice(const std::vector<AxisLog>& logs, const std::vector<AxisLog>& measured,
                          const AxisIdentificationOptions& options, AxisIdentification& run) {
  const std::string advice = kAxisOutputErrorAdvice;
  constexpr std::size_t kMaxTriedSamples = 200000;
  std::size_t samples = 0;
  for (const auto& log : logs) samples += log.time.size();
  std::optional<AxisIdentification> oe;
  std::string failure;
  for (auto& warning : run.fit.warnings) {
    const std::size_t at = warning.find(advice);
    if (warning.rfind("processing: ", 0) != 0 || at == std::string::npos) continue;
    if (samples > kMaxTriedSamples) {
      warning.insert(at + advice.size(), fmt::format(" (not tried here: {} samples)", samples));
      continue;
    }
    if (!oe && failure.empty()) {
      try {
        AxisIdentification trial;
        trial.section = run.section;
        FitByOutputError(logs, measured, measured, options, trial);
        oe = std::move(trial);
      } catch (const std::exception& e) {
        failure = ClippedText(e.what(), 160);
      }
    }
    const std::string name = warning.substr(12, warning.find(' ', 12) - 12);
    std::string tried;
    if (!oe) {
      tried = fmt::format("; tried: output error fails on these logs ({})", failure);
    } else {
      const ParameterEstimate *a = nullptr, *b = nullptr;
      for (const auto& e : run.fit.estimates) a = e.name == name ? &e : a;
      for (const auto& e : oe->fit.estimates) b = e.name == name ? &e : b;
      if (!a || !b) continue;
      const double z = std::abs(a->value - b->value) / std::hypot(a->standard_error, b->standard_error);
      tried = fmt::format("; tried: output error gives {} = {:.4g} +- {:.2g}{}", name, b->value, b->standard_error,
                          z <= 2.0 ? ", which agrees within 2 std"
                                   : fmt::format(", {:.3g} std away: the two methods disagree, trust neither on these "
                                                 "logs", z));
    }
    warning.insert(at + advice.size(), tried);
  }
}

}  // namespace

AxisMethod ChooseAxisMethod(const std::vector<AxisLog>& logs, AxisMethod requested, std::string* reason) {
  if (requested != AxisMethod::kAuto) return requested;
  const bool steps = std::all_of(logs.begin(), logs.end(), [](const AxisLog& l) { return IsTorqueStepLog(l); });
  if (reason) {
    *reason = steps ? "auto: the torque is held in steps (changes at < 2 % of the samples)"
                    : "auto: the torque varies (changes at >= 2 % of the samples)";
  }
  return steps ? AxisMethod::kOutputError : AxisMethod::kInverseDynamics;
}

namespace {

// The fit of `logs` (as logged, or re-timed at their status frames as
// `frames` says), `validation` likewise.
AxisIdentification IdentifyOn(const std::vector<AxisLog>& logged, const std::vector<AxisLog>& logs,
                              const StatusFrameRetiming& frames, const AxisSection& section,
                              const AxisIdentificationOptions& requested, const std::vector<AxisLog>& validation) {
  AxisIdentification run;
  const std::vector<AxisLog> measured = MeasuredRows(logs);
  run.section = section;
  AxisIdentificationOptions options = requested;
  // SysId logs in a length unit are of a linear mechanism (an elevator, a drivetrain).
  if (IsLengthUnit(options.sysid_unit)) run.section.linear = true;
  if (run.section.linear && IsAngleUnit(options.sysid_unit)) {
    throw OptionError(fmt::format("‹linear›: the log's position unit is '{}', an angle: a linear axis moves in a "
                                  "length (m); fit it as a rotary axis, or log the position in a length",
                                  options.sysid_unit));
  }
  const std::string mechanism = MechanismFreeSet(requested, run.section, options.axis.free);
  std::string reason = "asked for";
  run.method = ChooseAxisMethod(measured, options.method, &reason);
  if (options.method == AxisMethod::kAuto && frames.held_logs + frames.held_rates > 0) {
    run.method = AxisMethod::kOutputError;
    reason = "auto: status frames (output error compares the frames; inverse dynamics would differentiate them)";
  }
  if (run.method == AxisMethod::kOutputError) {
    if (!validation.empty()) throw OptionError("held-out logs are predicted by inverse dynamics: use the idim method");
    FitByOutputError(logs, measured, logged, options, run);
    if (frames.held_logs + frames.held_rates > 0) {
      AxisOeOptions oe_options;
      oe_options.free = options.axis.free;
      oe_options.fit = options.axis.fit;
      const std::string budget = AddStatusFrameBudget(logged, run.section, run.params, oe_options, run.fit);
      if (!budget.empty()) run.summary.push_back(budget);
      // The rule once more on the widened covariance (a widened std may
      // leave an estimate bounded only, or say nothing).
      DecideAxisDetermined(run.fit, kMaxRelativeStd, -1.0);
    }
  } else {
    FitByInverseDynamics(measured, options, MeasuredRows(validation), run);
    TryOutputErrorAdvice(logs, measured, options, run);
  }
  run.summary.insert(run.summary.begin(), fmt::format("method: {} ({})",
                                                      run.method == AxisMethod::kOutputError ? "output error" : "IDIM-LS",
                                                      reason));
  if (!mechanism.empty()) run.summary.push_back(mechanism);
  if (frames.held_rates > 0) {
    run.summary.push_back(fmt::format(
        "status frames: the logged velocity of {} of {} logs repeats between frames every {:.4g} ms while the "
        "position changes at every row: the velocity is left out and the position fitted (velocity from the "
        "position; docs/models.md#status-frames)",
        frames.held_rates, logs.size(), 1e3 * frames.frame_period));
  }
  if (frames.held_logs > 0) {
    run.summary.push_back(fmt::format(
        "status frames: the position of {} of {} logs repeats between frames every {:.4g} ms; each frame is measured "
        "once, half a logger step before its first row; the fit compares the {} frames ({}), with the effort of "
        "all {} rows{} (docs/models.md#status-frames)",
        frames.held_logs, logs.size(), 1e3 * frames.frame_period, frames.frames,
        std::any_of(logs.begin(), logs.end(), [](const AxisLog& l) { return !l.rate.empty(); })
            ? "position and the logged velocity"
            : "position; velocity not logged",
        frames.rows,
        frames.effort_framed > 0 ? fmt::format("; the effort of {} logs comes in {:.3g} ms frames too, each value "
                                               "taken to apply about its frame",
                                               frames.effort_framed, 1e3 * frames.effort_frame_period)
                                 : ""));
  }
  Interpret(options, run);
  StoreModelParameters(AxisParameterTable(), run.params, run.section);
  return run;
}

// Logs as logged whose position repeats between status frames: the rates lag
// the effort (docs/models.md#status-frames).
std::string StatusFrameWarning(const StatusFrameRetiming& frames, std::size_t logs, const std::string& why) {
  return fmt::format(
      "status frames: the position or velocity of {} of {} logs repeats for {:.3g} ms between a device's frames; "
      "output error at the frames was not used ({}), so the rows were fitted as logged: each value was measured up to a "
      "frame before the rows that repeat it, the rates lag the effort, which biases Ka and Ks by more than their std "
      "(docs/models.md#status-frames); log the position at the device's rate, or take these as approximate",
      frames.held_logs + frames.held_rates, logs, 1e3 * frames.frame_period, ClippedText(why, 200));
}

// A SysId Arm test logged in Rotations or Degrees (SysIdRoutine logs an
// angular mechanism in rotations): the gravity term is cos q of q in
// radians, so the logs are converted, q and q' times 2 pi (pi / 180), and the
// gains are per radian, as WPILib's ArmFeedforward takes them (Ks, Kg, the
// offset unchanged; Kv, Ka divided by the factor). Returns the factor, 1
// when there is nothing to convert.
double ArmRadiansPer(const AxisIdentificationOptions& options) {
  if (options.sysid_mechanism != "Arm") return 1.0;
  if (options.sysid_unit == "Rotations") return 2.0 * M_PI;
  if (options.sysid_unit == "Degrees") return M_PI / 180.0;
  return 1.0;
}

std::vector<AxisLog> InRadians(std::vector<AxisLog> logs, double factor) {
  for (auto& log : logs) {
    for (double& q : log.position) q *= factor;
    for (double& v : log.rate) v *= factor;
    log.start_rate *= factor;
  }
  return logs;
}

AxisIdentification IdentifyAxisAsGiven(const std::vector<AxisLog>& logged, const AxisSection& section,
                                       const AxisIdentificationOptions& requested, const std::vector<AxisLog>& held_out);

// AxisIdentification::rate_series of the logs the fit saw.
void AddSimulatedRates(const std::vector<AxisLog>& logs, const AxisIdentificationOptions& options,
                       AxisIdentification& run) {
  if (!options.simulate_rates) return;
  const std::vector<std::vector<double>> simulated = SimulateAxisLogRates(logs, run.params);
  for (std::size_t i = 0; i < logs.size(); ++i) {
    const AxisLog& log = logs[i];
    if (simulated[i].size() != log.time.size()) continue;
    PlotSeries series{log.path, log.time, log.rate, simulated[i]};
    if (series.measured.empty()) {
      series.measured = log.position;
      ApplyColumnOperation("derivative", log.time, series.measured);  // central differences, one-sided at the ends
    }
    run.rate_series.push_back(std::move(series));
  }
}

}  // namespace

AxisIdentification IdentifyAxis(const std::vector<AxisLog>& logged, const AxisSection& section,
                                const AxisIdentificationOptions& requested, const std::vector<AxisLog>& held_out) {
  RequireValid(requested);
  const double factor = ArmRadiansPer(requested);
  if (factor == 1.0) {
    AxisIdentification run = IdentifyAxisAsGiven(logged, section, requested, held_out);
    AddSimulatedRates(logged, requested, run);
    return run;
  }
  AxisIdentificationOptions in_radians = requested;
  in_radians.sysid_unit = "Radians";
  const std::vector<AxisLog> radians = InRadians(logged, factor);
  AxisIdentification run = IdentifyAxisAsGiven(radians, section, in_radians, InRadians(held_out, factor));
  AddSimulatedRates(radians, requested, run);
  run.summary.push_back(fmt::format("SysId Arm test logged in {}: converted to Radians (q and q' x {:.6g}) for the "
                                    "gravity term cos q; Kv and Ka are per radian, as WPILib's ArmFeedforward takes "
                                    "them (multiply by {:.6g} for per {})",
                                    requested.sysid_unit, factor, factor,
                                    requested.sysid_unit == "Rotations" ? "rotation" : "degree"));
  return run;
}

namespace {

AxisIdentification IdentifyAxisAsGiven(const std::vector<AxisLog>& logged, const AxisSection& section,
                                       const AxisIdentificationOptions& requested, const std::vector<AxisLog>& held_out) {
  std::vector<AxisLog> logs = logged, validation = held_out;
  const StatusFrameRetiming frames = RetimeStatusFrames(logs);
  RetimeStatusFrames(validation);
  if (frames.held_logs + frames.held_rates == 0 || requested.method != AxisMethod::kAuto) {
    return IdentifyOn(logged, logs, frames, section, requested, validation);
  }
  std::string why = "held-out logs are predicted by inverse dynamics";
  if (held_out.empty()) {
    try {
      return IdentifyOn(logged, logs, frames, section, requested, validation);
    } catch (const IdentificationError& e) {
      why = e.what();
    }
  }
  AxisIdentification run = IdentifyOn(logged, logged, {}, section, requested, held_out);
  run.fit.warnings.push_back(StatusFrameWarning(frames, logged.size(), why));
  return run;
}

}  // namespace

void TakeSysIdDeclarations(const std::vector<std::string>& units, const std::vector<std::string>& mechanisms,
                           AxisIdentificationOptions& options) {
  const bool sysid = !units.empty() && std::all_of(units.begin(), units.end(), [&](const std::string& u) {
    return !u.empty() && u == units.front();
  });
  if (!sysid) return;
  options.sysid_unit = units.front();
  if (std::all_of(mechanisms.begin(), mechanisms.end(), [&](const auto& m) { return m == mechanisms.front(); })) {
    options.sysid_mechanism = mechanisms.front();
  }
}

}  // namespace driveid
