#include "fit/joint/joint_fit.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include <fmt/format.h>

#include "core/clipped_text.h"
#include "core/errors.h"
#include "core/option_check.h"
#include "fit/core/adequacy.h"
#include "fit/axis/axis_rows.h"
#include "fit/joint/joint_mismatch.h"
#include "fit/core/linear_regression.h"
#include "fit/core/omitted_terms.h"
#include "models/missing_values.h"
#include "signal/butterworth.h"
#include "signal/resample.h"

namespace driveid {
namespace {

std::vector<std::string> JointColumnNames() {
  std::vector<std::string> names;
  for (const auto& row : JointParameterTable()) {
    if (row.in_model != nullptr) names.emplace_back(row.spec.key);
  }
  return names;
}

std::string JointAdvice(const std::vector<std::string>& involved) {
  std::vector<std::string> advice;
  const auto has = [&](const std::string& key) {
    return std::find(involved.begin(), involved.end(), key) != involved.end();
  };
  const auto key = [](double JointParameters::*member) { return KeyOf(JointParameterTable(), member); };
  if (has(key(&JointParameters::stiffness)) || has(key(&JointParameters::damping))) {
    advice.push_back("stiffness and damping need a deflection q_motor/n - q_link that moves: excite the joint near "
                     "its resonance, or log a link angle that resolves the deflection");
  }
  if (has("offset")) advice.push_back("the offset and Coulomb friction separate only with motion in both directions");
  if (has(key(&JointParameters::motor_inertia)) && has(key(&JointParameters::link_inertia))) {
    advice.push_back("only the total J_m + J_l is determined: fix one of them in ‹params› (a motor's data-sheet "
                     "inertia for motor_inertia) and leave it out of ‹free›");
  }
  return fmt::format("{}", fmt::join(advice, "; "));
}

}  // namespace

std::vector<std::string> JointDefaultFree(const std::vector<JointLog>& logs) {
  bool torque = false, link_torque = false;
  for (const auto& log : logs) {
    torque = torque || !log.torque.empty();
    link_torque = link_torque || !log.link_torque.empty();
  }
  const std::string offset = KeyOf(JointParameterTable(), &JointParameters::link_torque_offset);
  if (!torque) {
    return {KeyOf(JointParameterTable(), &JointParameters::stiffness),
            KeyOf(JointParameterTable(), &JointParameters::damping), offset};
  }
  auto free = FitParameterKeys(JointParameterTable(), "joint", true);
  if (link_torque) free.push_back(offset);
  return free;
}

namespace {

// The fit's columns and parameters: free ones from the start values (or
// their bound), fixed ones at their value; every fixed value the model needs
// and the file lacks named in one message. Several logs with a shaft torque:
// its offset (sensor bias + k x the initial twist of integrated angles) is
// each log's own, link_torque_offset_1 .. _L (the section keeps log 1's).
struct JointDesign {
  std::vector<std::string> columns = JointColumnNames();
  std::vector<FitParameter> parameters;
  std::map<std::string, double> fixed;
  double gear = 0.0;
  std::string offset_key = KeyOf(JointParameterTable(), &JointParameters::link_torque_offset);
  std::size_t offset_column = 0;
  bool per_log_offset = false;
  /// Shaft-torque rows only, for the fit whose warnings are shown (the
  /// printed one, not its per-log, sensitivity or trial variants): the motor
  /// and link accelerations, held at 0 in the fit and tested against its
  /// residuals (ShaftTorqueLocation), and an offset per kSensorDriftBlocks-th
  /// of each log, so that angles integrated from speeds (a random-walk
  /// deflection error) do not pass for a misplaced sensor; also held at 0.
  /// None (drift_columns empty) when no log has a shaft torque.
  std::size_t sensor_motor_column = 0, sensor_link_column = 0;
  std::vector<std::size_t> drift_first;  ///< per log: its first block column
  std::vector<std::string> drift_columns;
};

constexpr int kSensorDriftBlocks = 20;

constexpr const char* kSensorMotorAcceleration = "shaft torque: motor acceleration";
constexpr const char* kSensorLinkAcceleration = "shaft torque: link acceleration";

JointDesign MakeJointDesign(const std::vector<JointLog>& logs, const JointSection& start,
                            const std::vector<std::string>& free, bool sensor_test) {
  JointDesign d;
  bool has_torque = false;
  for (const auto& log : logs) has_torque = has_torque || !log.torque.empty();
  std::vector<const ParameterSpec*> needed;
  if (!start.gear_ratio || !(*start.gear_ratio > 0.0)) {
    needed.push_back(&SpecOf(JointParameterTable(), &JointSection::gear_ratio));
  }
  for (const auto& row : JointParameterTable()) {
    if (row.in_model == nullptr) continue;
    const std::optional<double> value = start.*(row.in_section);
    const bool is_free = std::find(free.begin(), free.end(), row.spec.key) != free.end();
    if (is_free) {
      d.parameters.push_back({row.spec.key, std::max(row.spec.lower_bound, value.value_or(0.0)), row.spec.lower_bound, 0.0});
    } else if (!value && row.spec.default_free && has_torque) {
      needed.push_back(&row.spec);
    }
    d.fixed[row.spec.key] = value.value_or(0.0);
  }
  if (!needed.empty()) {
    throw MissingValuesError("‹params›", "joint", needed, "(fixed in this fit)", " (or name the fitted ones in ‹free›)");
  }
  d.gear = *start.gear_ratio;
  d.offset_column = static_cast<std::size_t>(std::find(d.columns.begin(), d.columns.end(), d.offset_key) -
                                             d.columns.begin());
  const auto free_offset = std::find_if(d.parameters.begin(), d.parameters.end(),
                                        [&](const FitParameter& fp) { return fp.name == d.offset_key; });
  d.per_log_offset = logs.size() > 1 && free_offset != d.parameters.end();
  if (d.per_log_offset) {
    const FitParameter base = *free_offset;
    d.parameters.erase(free_offset);
    for (std::size_t i = 0; i < logs.size(); ++i) {
      FitParameter own = base;
      own.name = fmt::format("{}_{}", d.offset_key, i + 1);
      d.parameters.push_back(own);
      d.columns.push_back(own.name);
    }
  }
  const bool link_torque =
      std::any_of(logs.begin(), logs.end(), [](const JointLog& log) { return !log.link_torque.empty(); });
  if (link_torque && sensor_test) {
    d.sensor_motor_column = d.columns.size();
    d.columns.push_back(kSensorMotorAcceleration);
    d.sensor_link_column = d.columns.size();
    d.columns.push_back(kSensorLinkAcceleration);
    d.fixed[kSensorMotorAcceleration] = d.fixed[kSensorLinkAcceleration] = 0.0;
    for (std::size_t i = 0; i < logs.size(); ++i) {
      d.drift_first.push_back(d.columns.size());
      for (int b = 0; b < kSensorDriftBlocks; ++b) {
        d.drift_columns.push_back(fmt::format("shaft torque: log {} block {}", i + 1, b + 1));
        d.columns.push_back(d.drift_columns.back());
        d.fixed[d.drift_columns.back()] = 0.0;
      }
    }
  }
  return d;
}

// Irregular time stamps: the zero-phase filter needs a constant rate (never a silent 0 Hz cutoff).
[[noreturn]] void RefuseIrregularTime(const JointLog& log) {
  double shortest = INFINITY, longest = 0.0;
  for (std::size_t k = 1; k < log.time.size(); ++k) {
    shortest = std::min(shortest, log.time[k] - log.time[k - 1]);
    longest = std::max(longest, log.time[k] - log.time[k - 1]);
  }
  throw InputError(fmt::format("{}: time steps from {:.6g} to {:.6g} s (jitter {:.3g} % of the mean): the joint fit "
                               "filters at a constant rate; resample the log, or give ‹rate› HZ when the stamps "
                               "themselves are the noise",
                               log.path, shortest, longest,
                               100.0 * (longest - shortest) /
                                   ((log.time.back() - log.time.front()) / static_cast<double>(log.time.size() - 1))));
}

// Log i's rows: angles, rates and accelerations through the zero-phase
// filter, then equation 0 (motor) where the motor moves, 1 (total) where
// both move (each with the motor torque), 2 (shaft torque, no friction
// term) on every valid sample.
void AddJointLogRows(const JointLog& log, std::size_t i, const JointDesign& d, const JointFitOptions& options,
                     LinearRegression& regression, JointFitOutput& out) {
  if (log.time.size() < kMinAxisLogSamples) {
    throw InputError(fmt::format("{}: {} samples: the joint fit needs at least {}", log.path, log.time.size(),
                                 kMinAxisLogSamples));
  }
  AxisLog motor{log.path, log.time, log.motor_position, {}, {}}, link{log.path, log.time, log.link_position, {}, {}};
  for (double& q : motor.position) q /= d.gear;
  const AxisDerivatives dm = DifferentiateAxisLog(motor, options.cutoff, AxisPositionFilter::kButterworth);
  const AxisDerivatives dl = DifferentiateAxisLog(link, options.cutoff, AxisPositionFilter::kButterworth);
  if (dm.rate_hz == 0.0) RefuseIrregularTime(log);
  out.rate = dm.rate_hz;
  // The same zero-phase filter on the angles and the torque as on the rates.
  std::vector<double> theta_m = motor.position, theta_l = link.position, tau = log.torque, tau_link = log.link_torque;
  out.cutoff = dm.rate_hz > 0.0 ? (options.cutoff > 0.0 ? options.cutoff : dm.rate_hz / 40.0) : 0.0;
  if (dm.rate_hz > 0.0) {
    theta_m = ZeroPhaseLowPass(theta_m, out.cutoff, dm.rate_hz);
    theta_l = ZeroPhaseLowPass(theta_l, out.cutoff, dm.rate_hz);
    if (!tau.empty()) tau = ZeroPhaseLowPass(tau, out.cutoff, dm.rate_hz);
    if (!tau_link.empty()) tau_link = ZeroPhaseLowPass(tau_link, out.cutoff, dm.rate_hz);
  }
  // The zero-phase filter's start-up at both ends: two cutoff periods left out.
  const std::size_t edge = dm.rate_hz > 0.0 ? static_cast<std::size_t>(std::ceil(2.0 * dm.rate_hz / out.cutoff)) : 0;
  std::vector<char> valid(log.time.size(), 0);
  for (std::size_t k = edge; k + edge < log.time.size(); ++k) valid[k] = dm.valid[k] && dl.valid[k];
  double max_m = 0.0, max_l = 0.0;
  for (std::size_t k = 0; k < log.time.size(); ++k) {
    if (!valid[k]) continue;
    max_m = std::max(max_m, std::abs(dm.rate[k]));
    max_l = std::max(max_l, std::abs(dl.rate[k]));
  }
  const double floor_m = options.min_rate_fraction * max_m, floor_l = options.min_rate_fraction * max_l;
  for (int equation : {0, 1, 2}) {
    if ((equation < 2 && tau.empty()) || (equation == 2 && tau_link.empty())) continue;
    regression.BeginChannel(log.path + (equation == 0 ? ":motor" : equation == 1 ? ":total" : ":shaft torque"));
    for (std::size_t k = 0; k < log.time.size(); ++k) {
      const bool motor_moves = max_m > 0.0 && std::abs(dm.rate[k]) >= floor_m;
      const bool link_moves = max_l > 0.0 && std::abs(dl.rate[k]) >= floor_l;
      if (!valid[k] || (equation < 2 && !motor_moves) || (equation == 1 && !link_moves)) continue;
      const JointRegressors r = CalcJointRegressors(theta_m[k], dm.rate[k], dm.acceleration[k], theta_l[k],
                                                    dl.rate[k], dl.acceleration[k]);
      const auto& row = equation == 0 ? r.motor : equation == 1 ? r.total : r.link;
      const double target = equation == 2 ? tau_link[k] : d.gear * tau[k];
      std::vector<double> regressor(row.begin(), row.end());
      regressor.resize(d.columns.size(), 0.0);
      if (d.per_log_offset) std::swap(regressor[d.offset_column], regressor[kJointTerms + i]);
      if (equation == 2 && !d.drift_columns.empty()) {
        regressor[d.sensor_motor_column] = dm.acceleration[k];
        regressor[d.sensor_link_column] = dl.acceleration[k];
        const auto block = std::min<std::size_t>(kSensorDriftBlocks - 1, k * kSensorDriftBlocks / log.time.size());
        regressor[d.drift_first[i] + block] = 1.0;
      }
      regression.AddRow(regressor, target);
      out.time.push_back(log.time[k]);
      out.measured.push_back(target);
      out.equation.push_back(equation);
      out.log_index.push_back(static_cast<int>(i));
      out.motor_angle.push_back(log.motor_position[k]);
    }
  }
}

// What to do about a resonance near the cutoff, tried before it is said
// (docs/models.md#elastic-joint): the fit at a cutoff 2.5 x the resonance
// (below 0.4 x the rate) is advised only when it stands (not refused) and
// its own resonance lies below half that cutoff; otherwise output error or
// the frequency response, with what the trial showed.
std::string CutoffAdvice(const std::vector<JointLog>& logs, const JointSection& start, const JointFitOptions& options,
                         const JointFitOutput& out, double resonance) {
  const std::string elsewhere = "use ‹method› oe (output error differentiates nothing) or measure the frequency "
                                "response (drivetrain-fit frf)";
  if (!options.sensitivity) return elsewhere;  // a start or trial fit: nothing is printed from it
  const double raised = std::min(2.5 * resonance, 0.4 * out.rate);
  if (!(raised > 1.05 * out.cutoff)) {
    return fmt::format("the log's rate {:.4g} Hz leaves no higher cutoff to try; {}", out.rate, elsewhere);
  }
  JointFitOptions trial = options;
  trial.cutoff = raised;
  trial.per_log = trial.sensitivity = false;
  trial.refuse_undetermined = true;
  try {
    const JointFitOutput tried = FitJoint(logs, start, trial);
    const double moved = JointResonance(tried.params) / (2.0 * M_PI);
    if (std::isfinite(moved) && moved > 0.0 && raised >= 2.0 * moved) {
      return fmt::format("at ‹cutoff› {:.4g} the fit stands with stiffness {:.4g} and resonance {:.4g} Hz, clear of "
                         "the filter: raise ‹cutoff› to {:.4g}, or {}",
                         raised, tried.params.stiffness, moved, raised, elsewhere);
    }
    return fmt::format("a higher cutoff does not help (at {:.4g} Hz the resonance moves to {:.4g} Hz and stiffness to "
                       "{:.4g}): {}",
                       raised, moved, tried.params.stiffness, elsewhere);
  } catch (const std::exception& e) {
    std::string why = e.what();
    why = ClippedText(why, 120);
    return fmt::format("a higher cutoff does not help (at {:.4g} Hz the fit is refused: {}): {}", raised, why, elsewhere);
  }
}

// Adequacy (docs/models.md#adequacy): several logs each fitted alone and
// whether they agree; the same fit at half and twice the cutoff; a
// resonance near the cutoff.
void CheckJointAdequacy(const std::vector<JointLog>& logs, const JointSection& start, const JointFitOptions& options,
                        const JointDesign& d, JointFitOutput& out) {
  if (options.per_log && logs.size() > 1) {
    JointFitOptions alone = options;
    alone.per_log = alone.sensitivity = false;  // only its estimates are kept
    AddPerLogFits(out.fit, LogLabels(logs), [&](std::size_t i) {
      auto e = FitJoint({logs[i]}, start, alone).fit.estimates;
      // Each log's own offset is not a shared parameter to compare.
      if (d.per_log_offset) {
        e.erase(std::remove_if(e.begin(), e.end(), [&](const ParameterEstimate& x) { return x.name == d.offset_key; }),
                e.end());
      }
      return e;
    });
  }
  if (options.sensitivity) {
    for (const double factor : {0.5, 2.0}) {
      JointFitOptions other = options;
      other.cutoff = factor * out.cutoff;
      other.per_log = other.sensitivity = false;
      if (!(other.cutoff < 0.4 * out.rate)) continue;
      EstimateSet entry{fmt::format("cutoff {:.3g} Hz", other.cutoff), {}, "", other.cutoff};
      try {
        entry.estimates = FitJoint(logs, start, other).fit.estimates;
      } catch (const std::exception& e) {
        entry.failure = e.what();
      }
      out.fit.sensitivity.push_back(std::move(entry));
    }
    for (auto& w : ProcessingWarnings(out.fit, out.cutoff, "check the cutoff with ‹cutoff›: the resonance must lie "
                                                           "well below it")) {
      out.fit.warnings.push_back(std::move(w));
    }
  }
  const JointParameters& p = out.params;
  if (p.motor_inertia > 0.0 && p.link_inertia > 0.0 && p.stiffness > 0.0) {
    const double resonance = JointResonance(p) / (2.0 * M_PI);
    if (out.cutoff < 2.0 * resonance) {
      out.fit.warnings.push_back(fmt::format("the angle cutoff {:.4g} Hz is within a factor 2 of the fitted resonance "
                                             "{:.4g} Hz: the zero-phase filter biases the damping and stiffness there; "
                                             "{}",
                                             out.cutoff, resonance, CutoffAdvice(logs, start, options, out, resonance)));
    }
  }
}

// A shaft torque measured elsewhere than between the encoders
// (docs/models.md#elastic-joint): with an inertia J_s between the sensor and
// the spring on the motor side it reads k D + d D' + J_s theta_m'', on the
// link side k D + d D' - J_s theta_l''. Residuals of the shaft-torque rows
// that the accelerations explain (omitted-term test, share >= 5 %, beside
// an offset per block of each log: a slowly drifting deflection error, as
// from angles integrated from speeds, is not the sensor's place) say so,
// with the inertia each side implies.
std::optional<std::string> ShaftTorqueLocation(const LinearRegression& regression, const JointDesign& d,
                                               const std::map<std::string, double>& values, const FitResult& fit) {
  if (d.drift_columns.empty()) return std::nullopt;
  std::vector<std::string> free;
  for (const auto& e : fit.estimates) free.push_back(e.name);
  free.insert(free.end(), d.drift_columns.begin(), d.drift_columns.end());
  const OmittedTermTest t = TestOmittedTerm(regression, free, values, "shaft torque location",
                                            {kSensorMotorAcceleration, kSensorLinkAcceleration}, 0.05);
  if (!t.missing) return std::nullopt;
  return fmt::format(
      "model: the shaft torque's residual follows the accelerations ({:.0f} % of it; robust Wald {:.3g} > {:.3g}): "
      "it reads {:.3g} kg m^2 x the motor's and {:.3g} x the link's acceleration beyond the spring torque, so the "
      "sensor does not sit between the encoders (one on the motor side reads +J_s theta_m'', on the link side "
      "-J_s theta_l'', J_s the inertia between it and the spring); stiffness and damping fitted to it absorb that: "
      "fit from the motor torque, or log the torque where the encoders are",
      100.0 * t.share, t.wald, t.critical, t.coefficients[0], t.coefficients[1]);
}

}  // namespace

namespace {

// Logs whose stamps are regular but for isolated glitches, resampled onto
// their median step (the zero-phase filter needs a constant rate), each
// with a note.
std::vector<JointLog> RegularLogs(const std::vector<JointLog>& given, std::vector<std::string>& notes) {
  std::vector<JointLog> logs = given;
  for (auto& log : logs) {
    if (ConstantRate(log.time) > 0.0) continue;
    const double step = GlitchedStep(log.time);
    if (!(step > 0.0)) continue;
    const double rate = 1.0 / step;
    const auto count = static_cast<std::size_t>(std::floor((log.time.back() - log.time.front()) * rate)) + 1;
    for (auto* v : {&log.motor_position, &log.link_position, &log.torque, &log.link_torque, &log.motor_rate,
                    &log.link_rate}) {
      if (!v->empty()) *v = ResampleLinear(log.time, *v, rate, count);
    }
    std::vector<double> time(count);
    for (std::size_t k = 0; k < count; ++k) time[k] = log.time.front() + static_cast<double>(k) * step;
    log.time = std::move(time);
    notes.push_back(fmt::format("{}: isolated time-stamp glitches (intervals within {:.0f} % of the median step "
                                "{:.6g} s): resampled onto that step by linear interpolation",
                                log.path, 100.0 * kMaxGlitch, step));
  }
  return logs;
}

}  // namespace

bool JointFitOptions::IsValid(std::string* error) const {
  if (!(cutoff >= 0.0) || !std::isfinite(cutoff)) {
    *error = ViolatedConstraint("‹cutoff›", cutoff, "cutoff > 0 Hz (0: rate / 40)");
  } else if (!(min_rate_fraction >= 0.0 && min_rate_fraction < 1.0)) {
    *error = ViolatedConstraint("min_rate_fraction", min_rate_fraction, "0 <= fraction < 1");
  } else {
    return true;
  }
  return false;
}

JointFitOutput FitJoint(const std::vector<JointLog>& given_logs, const JointSection& start,
                        const JointFitOptions& given) {
  RequireValid(given);
  if (given_logs.empty()) throw OptionError("no logs given");
  std::vector<std::string> notes;
  const std::vector<JointLog> logs = RegularLogs(given_logs, notes);
  JointFitOptions options = given;
  if (options.free.empty()) options.free = JointDefaultFree(logs);
  CheckFreeNames(JointParameterTable(), "joint", options.free);
  const JointDesign d = MakeJointDesign(logs, start, options.free, options.sensitivity);
  JointFitOutput out;
  LinearRegression regression(d.columns);
  for (std::size_t i = 0; i < logs.size(); ++i) AddJointLogRows(logs[i], i, d, options, regression, out);
  if (regression.rows() <= d.parameters.size()) {
    throw IdentificationError(fmt::format("the logs leave {} usable rows for {} free parameters: the joint does not move",
                                          regression.rows(), d.parameters.size()));
  }
  FitOptions fit_options = options.fit;
  if (!fit_options.advice) fit_options.advice = JointAdvice;
  out.fit = regression.Fit(d.parameters, d.fixed, fit_options);
  out.fit.notes.insert(out.fit.notes.end(), notes.begin(), notes.end());
  std::map<std::string, double> values = d.fixed;
  for (const auto& e : out.fit.estimates) values[e.name] = e.value;
  if (d.per_log_offset) values[d.offset_key] = values[d.offset_key + "_1"];
  out.params = JointParameters{};
  for (const auto& row : JointParameterTable()) {
    if (row.in_model != nullptr) out.params.*(row.in_model) = values[row.spec.key];
  }
  std::vector<std::string> nonnegative;
  for (const auto& row : JointParameterTable()) {
    if (row.in_model != nullptr && row.spec.lower_bound == 0.0) nonnegative.emplace_back(row.spec.key);
  }
  CheckJointAdequacy(logs, start, options, d, out);
  if (auto warning = ShaftTorqueLocation(regression, d, values, out.fit)) out.fit.warnings.push_back(std::move(*warning));
  if (options.sensitivity || options.mismatch) {
    std::vector<std::string> free_names;
    for (const auto& e : out.fit.estimates) free_names.push_back(e.name);
    for (auto& w : JointMismatchWarnings(regression, free_names, values, out.equation, out.motor_angle)) {
      out.fit.warnings.push_back(std::move(w));
    }
  }
  std::map<std::string, double> start_values;  // the given start values, for a term at its bound
  for (const auto& row : JointParameterTable()) {
    if (row.in_section != nullptr && (start.*(row.in_section)).has_value()) {
      start_values[row.spec.key] = *(start.*(row.in_section));
    }
  }
  if (options.refuse_undetermined) {
    RequireDetermined(out.fit, nonnegative, kMaxRelativeStd, out.fit.warnings, start_values);
  }
  // The processing's spread in the intervals, after the refusal rule (which
  // judges what the data determine at the chosen cutoff; the processing
  // warnings say how the cutoff moves it).
  if (options.sensitivity) WidenForProcessing(out.fit, out.cutoff);
  out.model = regression.Predict(values);
  return out;
}

}  // namespace driveid
