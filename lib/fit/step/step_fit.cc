#include "fit/step/step_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <tuple>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/name_list.h"
#include "core/option_check.h"
#include "fit/step/step_residuals.h"
#include "logs/csv_log.h"
#include "sim/drivetrain_simulator.h"

namespace driveid {

bool StepFitOptions::IsValid(std::string* error) const { return OptionCheck(error).Nested(fit); }
namespace {

// The estimable parameters in enum order (sensitivity order), derived from
// the enum; tests/models/table_indices_test.cc checks it against the table.
std::vector<DriveTrainParameter> AllParameters() {
  std::vector<DriveTrainParameter> all;
  for (int e = 0; e < kDriveTrainParameterCount; ++e) all.push_back(static_cast<DriveTrainParameter>(e));
  return all;
}

// Model-specific advice for a non-identifiable set (docs/models.md#drive-train identifiability).
std::string StepAdvice(const std::vector<std::string>& involved) {
  std::vector<std::string> advice;
  const auto key = [](DriveTrainParameter parameter) { return std::string(DriveTrainParameterKey(parameter)); };
  const bool link = Contains(involved, key(DriveTrainParameter::kLinkStiffness));
  const bool gearbox = Contains(involved, key(DriveTrainParameter::kGearboxStiffness));
  if (link && gearbox) {
    advice.push_back("fix k_Tl or k_Tg with ‹params›: only their series combination enters the strain gauge's step "
                     "response; a logged link angle q_link separates them (docs/models.md#drive-train)");
  } else if ((link || gearbox) && (Contains(involved, key(DriveTrainParameter::kMotorInertia)) ||
                                    Contains(involved, key(DriveTrainParameter::kViscousFriction)))) {
    advice.push_back("a step response fixes only Theta_motor/k_eq and d_g/k_eq: fix the stiffness with ‹params›");
  }
  if (Contains(involved, "offset") || Contains(involved, "offset_1")) {
    advice.push_back("a per-log offset needs samples before the step to separate it from tau_c");
  }
  return fmt::format("{}", fmt::join(advice, "; "));
}

void CheckStepLog(const StepLog& log) {
  if (log.time.size() < kMinStepLogSamples) {
    throw InputError(fmt::format("{}: {} samples: a step log needs at least {}", log.path, log.time.size(),
                                 kMinStepLogSamples));
  }
  const bool steps = std::any_of(log.motor_torque.begin(), log.motor_torque.end(),
                                 [&](double u) { return u != log.motor_torque.front(); });
  if (!steps && log.motor_torque.front() == 0.0) {
    throw IdentificationError(fmt::format(
        "{}: column 'tau_motor' is zero throughout: the log holds no torque step to identify anything from",
        log.path));
  }
}

}  // namespace

namespace {

// Start of a log's offset from the data: the mean link torque over the
// samples before the motor torque first changes from 0, where the model
// rests at its zero state and predicts exactly 0 (0 without such samples).
// A long log's steady state fixes only offset + tau_c-side terms together;
// started at 0, a fit can settle on another branch (overshoot, then stick
// on the far side) that the short pre-step segment penalises too little.
double PreStepMean(const StepLog& log) {
  double sum = 0.0;
  std::size_t count = 0;
  while (count < log.time.size() && log.motor_torque[count] == 0.0) sum += log.link_torque[count++];
  return count == 0 || count == log.time.size() ? 0.0 : sum / static_cast<double>(count);
}

// Samples in the first transient of a log: up to the second change of the
// motor torque or ten 90 % rise times of the link torque after the first
// change (at least 10 samples), whichever comes first. Its length follows
// the drive's own time scale, read from the data, not the log's length.
std::size_t FirstTransientLength(const StepLog& log) {
  const std::size_t n = log.time.size();
  std::size_t first = 0;
  while (first < n && log.motor_torque[first] == log.motor_torque.front()) ++first;
  if (first == n) first = 0;  // torque held from the start: its transient begins at once
  std::size_t end = first + 1;
  while (end < n && log.motor_torque[end] == log.motor_torque[first]) ++end;
  if (end - first < 20) return n;
  const double before = PreStepMean(log);
  double after = 0.0;
  const std::size_t tail = std::max<std::size_t>(1, (end - first) / 5);
  for (std::size_t k = end - tail; k < end; ++k) after += log.link_torque[k];
  after /= static_cast<double>(tail);
  std::size_t rise = first;
  while (rise < end && std::abs(log.link_torque[rise] - before) < 0.9 * std::abs(after - before)) ++rise;
  const double rise_time = std::max(log.time[rise < end ? rise : end - 1] - log.time[first],
                                    10.0 * (log.time[first + 1] - log.time[first]));
  std::size_t stop = first;
  while (stop < end && log.time[stop] - log.time[first] <= 10.0 * rise_time) ++stop;
  return stop;
}

// The first `length` samples of a log (copied, nothing more).
StepLog Prefix(const StepLog& log, std::size_t length) {
  const auto head = [length](const std::vector<double>& v) {
    return std::vector<double>(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(std::min(length, v.size())));
  };
  return {log.path, head(log.time), head(log.motor_torque), head(log.link_torque), head(log.motor_angle),
          head(log.link_angle)};
}

// One solve from `start` (offsets from `start_offsets`, 0 when empty).
StepFitOutput FitFrom(const std::vector<StepLog>& logs, const DriveTrainParameters& start,
                      const std::vector<double>& start_offsets, DriveTrainModel model,
                      const std::vector<std::string>& free, const FitOptions& options,
                      DriveTrainIntegration integration) {
  std::vector<DriveTrainParameter> ode_parameters;
  std::vector<FitParameter> fit_parameters;
  for (auto parameter : AllParameters()) {
    const std::string key = DriveTrainParameterKey(parameter);
    if (!Contains(free, key)) continue;
    const double value = GetDriveTrainParameter(start, parameter);
    if (!(value > 0.0)) {
      throw InputError(fmt::format("‹free› {}: the starting value in ‹params› must be > 0, got {}", key, value));
    }
    ode_parameters.push_back(parameter);
    // Friction may vanish; inertias and stiffnesses must stay strictly positive.
    const bool may_vanish = parameter == DriveTrainParameter::kViscousFriction ||
                            parameter == DriveTrainParameter::kCoulombFriction;
    fit_parameters.push_back({key, value, may_vanish ? 0.0 : 1e-6 * value, 0.0});
  }
  const bool fit_offsets = Contains(free, "offset");
  if (fit_offsets) {
    double scale = 0.0;
    for (const auto& log : logs) {
      for (double y : log.link_torque) scale = std::max(scale, std::abs(y));
    }
    for (std::size_t i = 0; i < logs.size(); ++i) {
      const double initial = i < start_offsets.size() ? start_offsets[i] : PreStepMean(logs[i]);
      fit_parameters.push_back({fmt::format("offset_{}", i + 1), initial, -std::numeric_limits<double>::infinity(),
                                std::max(1e-3 * scale, 1e-9)});
    }
  }

  const std::unique_ptr<StepFitResiduals> made =
      MakeStepFitResiduals(logs, start, model, ode_parameters, fit_offsets, options.large);
  StepFitResiduals& residuals = *made;
  residuals.set_integration(integration);
  const std::vector<FitChannel> channels = residuals.Channels();
  FitOptions fit_options = options;
  if (!fit_options.advice) fit_options.advice = StepAdvice;

  StepFitOutput output;
  // Several logs with offsets: a block per log, the offsets eliminated by
  // the Schur complement (time and memory linear in the number of logs).
  output.fit = fit_offsets && logs.size() > 1
                   ? FitBlockLeastSquares(residuals, fit_parameters, channels, fit_options)
                   : FitLeastSquares(residuals, fit_parameters, channels, fit_options);
  residuals.UnweightRmse(output.fit);
  std::vector<double> estimate;
  for (const auto& e : output.fit.estimates) estimate.push_back(e.value);
  output.params = start;
  for (std::size_t j = 0; j < ode_parameters.size(); ++j) SetDriveTrainParameter(output.params, ode_parameters[j], estimate[j]);
  output.offsets.assign(logs.size(), 0.0);
  for (std::size_t i = 0; i < logs.size(); ++i) {
    if (fit_offsets) output.offsets[i] = estimate[ode_parameters.size() + i];
    output.simulated.push_back(residuals.Simulate(i, estimate.data()));
  }
  return output;
}

// The parameters of the full model's fit that the reduced model determines
// as well (it has no Theta_g, and k_Tl, k_Tg enter it only as k_eq).
std::vector<std::string> ReducedStageFree(const std::vector<std::string>& free) {
  std::vector<std::string> out;
  for (const auto& key : free) {
    if (key == DriveTrainParameterKey(DriveTrainParameter::kGearboxInertia) ||
        key == DriveTrainParameterKey(DriveTrainParameter::kLinkStiffness) ||
        key == DriveTrainParameterKey(DriveTrainParameter::kGearboxStiffness)) {
      continue;
    }
    out.push_back(key);
  }
  return out;
}

std::string DescribeOptimum(const StepFitOutput& o) {
  std::vector<std::string> parts;
  for (const auto& e : o.fit.estimates) {
    if (parts.size() == 4) {
      parts.push_back("...");
      break;
    }
    parts.push_back(fmt::format("{} {:.4g}", e.name, e.value));
  }
  return fmt::format("cost {:.6g}: {}", o.fit.cost, fmt::join(parts, ", "));
}

// Do two optima differ by more than their statistics allow (any estimate
// further apart than 3 of the kept fit's standard errors, or the cost by
// more than 0.1 %)?
bool Disagree(const StepFitOutput& kept, const StepFitOutput& other) {
  if (std::abs(other.fit.cost - kept.fit.cost) > 1e-3 * kept.fit.cost) return true;
  for (std::size_t j = 0; j < kept.fit.estimates.size(); ++j) {
    const auto& a = kept.fit.estimates[j];
    const double difference = std::abs(a.value - other.fit.estimates[j].value);
    if (difference > 3.0 * a.standard_error + 1e-9 * std::abs(a.value)) return true;
  }
  return false;
}

}  // namespace

namespace {

// The staged start (see FitStepResponses): the reduced model on each log's
// first transient, then (full model) the full model on the same transients,
// then the model on the whole logs. `transient_fit` is the last stage on the
// transients; a failure is kept in `failure`.
struct StagedFit {
  std::optional<StepFitOutput> fit, transient_fit;
  std::string failure;
};

StagedFit FitStaged(const std::vector<StepLog>& logs, const std::vector<std::size_t>& transient_lengths,
                    const DriveTrainParameters& start, const StepFitOptions& options) {
  StagedFit out;
  const bool full = options.model == DriveTrainModel::kFull;
  const std::vector<std::string> reduced_free = full ? ReducedStageFree(options.free) : options.free;
  if (reduced_free.empty()) return out;
  try {
    FitOptions quiet = options.fit;
    quiet.progress = nullptr;
    StepFitOutput stage;
    {
      // The transients live only as long as their fits.
      std::vector<StepLog> transients;
      for (std::size_t i = 0; i < logs.size(); ++i) transients.push_back(Prefix(logs[i], transient_lengths[i]));
      stage = FitFrom(transients, start, {}, DriveTrainModel::kReduced, reduced_free, quiet, options.integration);
      if (full) {
        const int reduced_iterations = stage.fit.iterations;
        stage = FitFrom(transients, stage.params, stage.offsets, options.model, options.free, quiet,
                        options.integration);
        stage.fit.iterations += reduced_iterations;
      }
    }
    out.fit = FitFrom(logs, stage.params, stage.offsets, options.model, options.free, options.fit,
                      options.integration);
    out.fit->fit.iterations += stage.fit.iterations;  // the whole path
    out.transient_fit = std::move(stage);
  } catch (const IdentificationError& e) {
    out.failure = e.what();
  }
  return out;
}

// Does the rest of the log pull the estimates away from what the first
// transients alone say (by more than 3 of their standard errors)?
void WarnIfTransientsMoved(const StepFitOutput& transient_fit, StepFitOutput& staged) {
  std::vector<std::string> moved;
  for (std::size_t j = 0; j < staged.fit.estimates.size() && j < transient_fit.fit.estimates.size(); ++j) {
    const auto& a = transient_fit.fit.estimates[j];
    const auto& b = staged.fit.estimates[j];
    if (a.name == b.name && std::abs(b.value - a.value) > 3.0 * a.standard_error) {
      moved.push_back(fmt::format("{} {:.4g} +- {:.2g} -> {:.4g}", a.name, a.value, a.standard_error, b.value));
    }
  }
  if (!moved.empty()) {
    staged.fit.warnings.push_back(fmt::format(
        "the whole logs pull the estimates away from the first transients' ({}): the model may miss something "
        "over the long run, or the cost has several optima (check with ‹starts› both; docs/models.md#drive-train)",
        fmt::join(moved, ", ")));
  }
}

// Of the staged and the given start's fits, the lower cost, with a warning
// when they disagree.
StepFitOutput KeepLowerCost(StepFitOutput staged, StepFitOutput given) {
  const bool staged_better = staged.fit.cost <= given.fit.cost;
  StepFitOutput kept = staged_better ? std::move(staged) : std::move(given);
  const StepFitOutput& other = staged_better ? given : staged;
  if (Disagree(kept, other)) {
    kept.fit.warnings.push_back(fmt::format(
        "starts disagree: from {} {}; from {} {}; kept the lower cost", staged_better ? "the staged start" : "the given start",
        DescribeOptimum(kept), staged_better ? "the given start" : "the staged start", DescribeOptimum(other)));
  }
  return kept;
}

}  // namespace

StepFitOutput FitStepResponses(const std::vector<StepLog>& logs, const DriveTrainParameters& start,
                               const StepFitOptions& options) {
  RequireValid(options);
  if (logs.empty()) throw OptionError("no step logs given");
  CheckFreeNames(DriveTrainParameterTable(), "step", options.free, {"offset"});
  for (const auto& log : logs) CheckStepLog(log);
  if (options.model == DriveTrainModel::kFull && !(start.gearbox_inertia > 0.0)) {
    throw InputError("the full model needs drivetrain.Theta_g > 0 in ‹params›");
  }
  if (options.model == DriveTrainModel::kReduced &&
      Contains(options.free, DriveTrainParameterKey(DriveTrainParameter::kGearboxInertia))) {
    throw IdentificationError("Theta_g has no effect in the reduced model (it sets Theta_g = 0): use ‹model› full");
  }
  if (options.starts == StepStarts::kGiven) {
    return FitFrom(logs, start, {}, options.model, options.free, options.fit, options.integration);
  }

  // Long logs (docs/models.md#drive-train, "Starting on long logs"): once
  // the drive sticks, the rest of the log weighs the stuck level, which
  // moves in jumps with tau_c and the dynamics (another reversal before
  // sticking), and the full model's undamped link mode rings on with a phase
  // set by the sticking instant; the cost then has neighbouring optima a few
  // times off the truth (reduced, 2 s at 100 kHz: d_g 0.007 for 0.016; full,
  // 2 s at 5 kHz: tau_c near 1, offset near 5 for 5 and 1.3). The staged
  // start: the reduced model (no ringing) fitted to each log's first
  // transient, then (full model) the full model on the same transients,
  // then the model on the whole logs. The fit also runs from the given
  // start; the lower cost wins and a disagreement is reported.
  std::vector<std::size_t> transient_lengths;
  bool shorter = false;
  for (const auto& log : logs) {
    transient_lengths.push_back(FirstTransientLength(log));
    shorter = shorter || transient_lengths.back() < log.time.size();
  }
  if (options.model != DriveTrainModel::kFull && !shorter) {
    return FitFrom(logs, start, {}, options.model, options.free, options.fit, options.integration);
  }
  StagedFit staged = FitStaged(logs, transient_lengths, start, options);
  if (staged.fit && options.starts == StepStarts::kStaged) {
    if (staged.transient_fit) WarnIfTransientsMoved(*staged.transient_fit, *staged.fit);
    return std::move(*staged.fit);
  }
  std::optional<StepFitOutput> given;
  std::string given_failure;
  try {
    given = FitFrom(logs, start, {}, options.model, options.free, options.fit, options.integration);
  } catch (const IdentificationError& e) {
    if (!staged.fit) throw;
    given_failure = e.what();
  }
  if (!staged.fit) {
    if (!staged.failure.empty()) {
      given->fit.warnings.push_back("the staged start failed (" + staged.failure +
                                    "); the fit ran from the given start only");
    }
    return std::move(*given);
  }
  if (!given) {
    staged.fit->fit.warnings.push_back("from the given start the fit failed (" + given_failure +
                                       "); kept the fit from the staged start");
    return std::move(*staged.fit);
  }
  return KeepLowerCost(std::move(*staged.fit), std::move(*given));
}

}  // namespace driveid
