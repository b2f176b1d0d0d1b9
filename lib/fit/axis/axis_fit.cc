#include "fit/axis/axis_fit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>
#include <tuple>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/name_list.h"
#include "core/option_check.h"
#include "core/order_statistics.h"
#include "fit/core/adequacy.h"
#include "fit/axis/axis_adequacy.h"
#include "fit/axis/axis_rows.h"
#include "fit/core/linear_regression.h"
#include "fit/core/omitted_terms.h"
#include "logs/csv_log.h"
#include "models/missing_values.h"
#include "signal/resample.h"
#include "models/axis_term.h"
#include "signal/butterworth.h"
#include "signal/local_polynomial.h"

namespace driveid {

bool AxisFitOptions::IsValid(std::string* error) const {
  if (decimation < 0) {
    *error = ViolatedConstraint("‹decimation›", decimation, ">= 1 (0: from the logs)");
  } else if (!(cutoff >= 0.0) || !std::isfinite(cutoff)) {
    *error = ViolatedConstraint("‹cutoff›", cutoff, "cutoff > 0 Hz (0: from the data)");
  } else if (!(min_rate_fraction >= 0.0 && min_rate_fraction < 1.0)) {
    *error = ViolatedConstraint("min_rate_fraction", min_rate_fraction, "0 <= fraction < 1");
  } else if (!(std::abs(torque_delay) <= kMaxTorqueDelay)) {
    *error = ViolatedConstraint("‹torque-timing›", torque_delay, "a delay from -1 to 1 samples");
  } else {
    return true;
  }
  return false;
}

namespace {

// The regressor columns: the linear parameters, in index order.
const AxisRow& Column(std::size_t j) { return AxisTermRow(j); }

}  // namespace

namespace {

// Rows built for the same logs, decimation and rate floor, by cutoff,
// timing and each log's reach (AxisRowReaches): the cutoff search builds
// each candidate's, and the central fit and the half/twice sensitivity fits
// take them from here (the candidates double, so half and twice the chosen
// one are usually among them; at the band the search's rows are the fit's).
// Rows larger than kCachedRowBytes are not kept.
using AxisRowCache =
    std::map<std::tuple<double, AxisTorqueTiming, double, std::vector<int>>, std::shared_ptr<const AxisRows>>;
constexpr std::size_t kCachedRowBytes = std::size_t{64} << 20;

// What a fit at one cutoff does beyond the estimates: the adequacy checks
// and the per-log fits (a candidate of the cutoff search needs neither).
enum class AtCutoff { kFull, kScore };

AxisFitOutput FitAtCutoff(const std::vector<AxisLog>& logs, const AxisSection& start, const AxisFitOptions& options,
                          AxisRowCache* cache, AtCutoff extent, AxisReach reach = AxisReach::kAtCutoff);

double ChooseCutoff(const std::vector<AxisLog>& logs, const AxisSection& start, const AxisFitOptions& options,
                    AxisRowCache* cache) {
  // Of the candidates (axis_rows.h), the highest unless a lower one's fit
  // leaves a mean squared residual of the (identically filtered) torque
  // smaller by more than kAxisLowerCutoffGain: lower cutoffs take the encoder's
  // noise out of q'', but distort the motion and leave out more around each
  // reversal (AxisExclusionReach), so they must clearly win (candidates
  // that nearly tie would otherwise trade places from log to log, and the
  // rows with them). Every candidate is scored on the rows clear of
  // reversals by the reach at the band (AxisReach::kAtBand): with its own,
  // longer reach a lower cutoff would leave out its own worst rows and win
  // for that alone.
  const std::vector<double> candidates = AxisCutoffCandidates(logs, options.decimation);
  if (candidates.size() < 2) return candidates.empty() ? 0.0 : candidates.front();
  AxisFitOptions trial = options;
  trial.per_log = false;
  trial.sensitivity = false;
  return PickAxisCutoff(candidates, [&](double cutoff) {
    trial.cutoff = cutoff;
    try {
      const FitResult fit = FitAtCutoff(logs, start, trial, cache, AtCutoff::kScore, AxisReach::kAtBand).fit;
      int rows = 0;
      for (const auto& channel : fit.channels) rows += channel.samples;
      return rows > 0 ? 2.0 * fit.cost / rows : HUGE_VAL;
    } catch (const std::exception&) {
      // A candidate the data refuse does not win; FitAxis reports the chosen one's errors.
      return HUGE_VAL;
    }
  });
}

// (axis_rows.h kFromData) At options.cutoff, when the logged torque acts,
// among the readings kTimingReadings (samples after its stamp: -0.5 a
// command held since the last sample, as ros2_control logs it; 0 sampled;
// +0.5 held). Each fits the same dependent column, the torque's two-sample
// mean, against the regressors moved to when it acts (kDelayed), so their
// costs compare: residual sums of squares, each residual clipped at
// kTimingClip robust std so that a start-up transient does not decide.
// The evidence against reading i is its cost above the best in units of the
// best's residual variance, divided by the square of the residuals' std
// inflation (fewer independent rows); each reading weighs exp(-evidence/2)
// (normalised), and the timing's uncertainty enters the covariance as the
// weighted spread of the estimates between the readings (AddTimingCovariance).
// The cost is not profiled over a continuous delay: under feedback the
// measured position's noise is in both the torque and the regressors, and a
// regressor moved earlier than the torque correlates with it, so the cost
// keeps falling past the true delay (a held 1 kHz log's minimum runs to +1).
constexpr double kTimingClip = 4.0;
constexpr std::array<double, 3> kTimingReadings = {-0.5, 0.0, 0.5};
// Readings weighing less are left out of the covariance.
constexpr double kTimingMinWeight = 1e-4;

struct TorqueDelayEstimate {
  double delay = 0.5;  ///< the best reading [samples]
  std::vector<double> delays, weights;  ///< the readings fitted and their weights
  std::string rule;
};

TorqueDelayEstimate EstimateTorqueDelay(const std::vector<AxisLog>& logs, const AxisSection& start,
                                        const AxisFitOptions& options, AxisRowCache* cache) {
  AxisFitOptions trial = options;
  trial.per_log = false;
  trial.sensitivity = false;
  trial.torque_timing = AxisTorqueTiming::kDelayed;
  std::vector<std::vector<double>> residual(kTimingReadings.size());
  std::vector<double> inflation(kTimingReadings.size(), 1.0);
  for (std::size_t i = 0; i < kTimingReadings.size(); ++i) {
    trial.torque_delay = kTimingReadings[i];
    try {
      const AxisFitOutput fit = FitAtCutoff(logs, start, trial, cache, AtCutoff::kScore);
      for (std::size_t r = 0; r < fit.measured.size(); ++r) residual[i].push_back(fit.measured[r] - fit.model[r]);
      for (const auto& channel : fit.fit.channels) inflation[i] = std::max(inflation[i], channel.inflation);
    } catch (const std::exception&) {
      // A reading the data refuse does not win.
    }
  }
  std::vector<double> magnitude;
  std::size_t rows = 0;
  for (const auto& r : residual) {
    for (double x : r) magnitude.push_back(std::abs(x));
    rows = std::max(rows, r.size());
  }
  TorqueDelayEstimate out;
  if (magnitude.empty()) {
    out.rule = "no reading could be fitted to judge: held (+0.5) kept";
    return out;
  }
  const double clip = kTimingClip * RobustStd(std::move(magnitude));
  std::vector<double> cost(kTimingReadings.size(), HUGE_VAL);
  for (std::size_t i = 0; i < kTimingReadings.size(); ++i) {
    if (residual[i].size() != rows) continue;
    cost[i] = 0.0;
    for (double x : residual[i]) cost[i] += 0.5 * std::min(x * x, clip * clip);
  }
  const auto best = static_cast<std::size_t>(std::min_element(cost.begin(), cost.end()) - cost.begin());
  out.delay = kTimingReadings[best];
  std::vector<std::string> said;
  double total = 0.0;
  for (std::size_t i = 0; i < kTimingReadings.size(); ++i) {
    const double evidence = std::isfinite(cost[i]) && cost[best] > 0.0
                                ? (cost[i] - cost[best]) * static_cast<double>(rows) / cost[best] /
                                      (inflation[best] * inflation[best])
                                : HUGE_VAL;
    const double weight = std::exp(-0.5 * evidence);
    out.delays.push_back(kTimingReadings[i]);
    out.weights.push_back(weight);
    total += weight;
    if (i != best) said.push_back(fmt::format("{:+.1f}: {:.3g}", kTimingReadings[i], evidence));
  }
  for (double& w : out.weights) w /= total;
  out.rule = fmt::format("from the data at the cutoff {:.4g} Hz: of the readings -0.5 (a command held since the last "
                         "sample), 0 (sampled) and +0.5 (held) samples after the stamp, {:+.1f} leaves the smallest "
                         "clipped residual sum of squares; evidence against the others {} residual variances; "
                         "their weighted spread is in the intervals",
                         options.cutoff, out.delay, fmt::join(said, ", "));
  return out;
}

// The timing's uncertainty in the covariance: for each other reading i of
// weight w_i, the estimates' move theta_i - theta_best enters as a
// systematic error with g = sqrt(w_i) (theta_i - theta_best), sigma 1
// (adequacy.h AddSystematicCovariance): the covariance of a mixture over the
// readings, about the best one.
void AddTimingCovariance(const std::vector<AxisLog>& logs, const AxisSection& start, const AxisFitOptions& central,
                         const TorqueDelayEstimate& timing, AxisRowCache* cache, FitResult& fit) {
  for (std::size_t i = 0; i < timing.delays.size(); ++i) {
    if (timing.delays[i] == central.torque_delay || !(timing.weights[i] >= kTimingMinWeight)) continue;
    AxisFitOptions other = central;
    other.per_log = false;
    other.torque_delay = timing.delays[i];
    FitResult alternative;
    try {
      alternative = FitAtCutoff(logs, start, other, cache, AtCutoff::kScore).fit;
    } catch (const std::exception&) {
      continue;  // a reading the data refuse adds nothing
    }
    std::vector<double> gradient;
    for (const auto& e : fit.estimates) {
      double moved = e.value;
      for (const auto& o : alternative.estimates) {
        if (o.name == e.name) moved = o.value;
      }
      gradient.push_back(std::sqrt(timing.weights[i]) * (moved - e.value));
    }
    AddSystematicCovariance(fit, gradient, 1.0);
  }
}

}  // namespace

namespace {

// Whether UniformAxisLogs resamples `log`, and onto which step [s].
bool JittersAboutStep(const AxisLog& log, double* step_out) {
  const std::size_t n = log.time.size();
  if (n < 3 || !log.measured.empty() || ConstantRate(log.time) > 0.0) return false;
  const double step = (log.time.back() - log.time.front()) / static_cast<double>(n - 1);
  // Only where every sample is kept (below 2 x kAxisDecimatedRate): there
  // the local polynomial's window spans too few samples; faster logs keep
  // the irregular path, whose decimated rows it serves.
  if (!(step > 0.0) || !std::isfinite(step) || !(1.0 / step < 2.0 * kAxisDecimatedRate)) return false;
  std::size_t off = 0;
  for (std::size_t k = 1; k < n; ++k) {
    const double dt = log.time[k] - log.time[k - 1];
    if (!(dt > 0.0) || dt > 2.5 * step) return false;
    if (std::abs(dt - step) > 0.5 * step) ++off;
  }
  *step_out = step;
  return !(static_cast<double>(off) > 0.05 * static_cast<double>(n - 1));
}

}  // namespace

const std::vector<AxisLog>& UniformAxisLogs(const std::vector<AxisLog>& logs, std::vector<AxisLog>& storage,
                                            std::vector<std::string>* notes) {
  double step = 0.0;
  if (std::none_of(logs.begin(), logs.end(), [&](const AxisLog& log) { return JittersAboutStep(log, &step); })) {
    return logs;
  }
  storage = logs;
  for (AxisLog& log : storage) {
    const std::size_t n = log.time.size();
    if (!JittersAboutStep(log, &step)) continue;
    const double rate = 1.0 / step;
    for (auto* v : {&log.position, &log.force, &log.rate}) {
      if (!v->empty()) *v = ResampleLinear(log.time, *v, rate, n);
    }
    const double first = log.time.front();
    for (std::size_t k = 0; k < n; ++k) log.time[k] = first + static_cast<double>(k) * step;
    if (notes) {
      notes->push_back(fmt::format("{}: time stamps jitter about {:.4g} ms: resampled onto that step by linear "
                                   "interpolation (docs/models.md#axis-decimation)",
                                   log.path, 1e3 * step));
    }
  }
  return storage;
}

int ChooseAxisDecimation(const std::vector<AxisLog>& logs, std::string* rule) {
  const double rate = AxisSamplingRate(logs);
  std::size_t shortest = 0;
  for (std::size_t i = 0; i < logs.size(); ++i) {
    if (logs[i].time.size() < logs[shortest].time.size()) shortest = i;
  }
  const std::size_t samples = logs.empty() ? 0 : logs[shortest].time.size();
  const int by_rate = std::isfinite(rate) && rate > 0.0
                          ? std::clamp(static_cast<int>(std::floor(rate / kAxisDecimatedRate)), 1, kAxisDecimation)
                          : kAxisDecimation;
  const int by_length = std::max(1, static_cast<int>(samples / static_cast<std::size_t>(kAxisRowsPerLog)));
  const int decimation = std::min(by_rate, by_length);
  if (rule) {
    *rule = by_length < by_rate
                ? fmt::format("from the logs: the shortest ({}, {} samples) keeps at least {} rows", logs[shortest].path,
                              samples, kAxisRowsPerLog)
                : fmt::format("from the logs: their rate {:.4g} Hz decimated to no less than {:g} Hz (at most every "
                              "{}th sample)",
                              rate, kAxisDecimatedRate, kAxisDecimation);
  }
  return decimation;
}

int AxisDecimationFor(const std::vector<AxisLog>& logs, int requested, std::string* rule) {
  if (requested != kAxisDecimationFromLogs) {
    if (rule) *rule = "given (‹decimation›)";
    return requested;
  }
  return ChooseAxisDecimation(logs, rule);
}

double ChooseAxisCutoff(const std::vector<AxisLog>& given, const AxisSection& start, const AxisFitOptions& options) {
  std::vector<AxisLog> storage;
  const std::vector<AxisLog>& logs = UniformAxisLogs(given, storage, nullptr);
  AxisRowCache cache;
  AxisFitOptions o = options;
  o.decimation = AxisDecimationFor(logs, options.decimation, nullptr);
  return ChooseCutoff(logs, start, o, &cache);
}

AxisFitOutput FitAxis(const std::vector<AxisLog>& given, const AxisSection& start, const AxisFitOptions& options) {
  if (given.empty()) throw OptionError("no logs given");
  std::vector<std::string> resampled;
  std::vector<AxisLog> storage;
  const std::vector<AxisLog>& logs = UniformAxisLogs(given, storage, &resampled);
  AxisFitOptions central = options;
  central.sensitivity = false;
  std::string decimation_rule;
  central.decimation = AxisDecimationFor(logs, options.decimation, &decimation_rule);
  CheckFreeNames(AxisParameterTable(), "axis", options.free);
  AxisRowCache cache;
  std::string timing_rule = "given (‹torque-timing›)";
  TorqueDelayEstimate timing;
  if (options.torque_timing == AxisTorqueTiming::kFromData) {
    // The timing first, judged at twice the decimated band (below 0.4 x
    // rate; the given cutoff if higher), where the position filter no
    // longer shapes the band the rows keep: at or below it, its attenuation
    // of q'' next to the unfiltered torque favours the held reading on
    // sampled logs. Then the cutoff with that timing.
    // Judged on rows decimated by kAxisDecimation unless the decimation was
    // given (the readings' residuals separate there; the fit then keeps the
    // decimation chosen for the logs).
    AxisFitOptions judged = central;
    if (options.decimation == kAxisDecimationFromLogs) judged.decimation = kAxisDecimation;
    const double rate = AxisSamplingRate(logs);
    judged.cutoff =
        std::max(options.cutoff, std::min(2.0 * AxisDecimatedBand(rate, judged.decimation), AxisHighestCutoff(logs)));
    timing = EstimateTorqueDelay(logs, start, judged, &cache);
    central.torque_timing = AxisTorqueTiming::kDelayed;
    central.torque_delay = timing.delay;
    timing_rule = timing.rule;
  }
  central.cutoff = options.cutoff > 0.0 ? options.cutoff : ChooseCutoff(logs, start, central, &cache);
  AxisFitOutput out = FitAtCutoff(logs, start, central, &cache, AtCutoff::kFull);
  out.torque_timing = central.torque_timing;
  out.torque_delay = central.torque_delay;
  out.timing_rule = timing_rule;
  out.decimation = central.decimation;
  out.decimation_rule = decimation_rule;
  for (const std::string& note : resampled) out.fit.notes.push_back(note);
  out.cutoff_rule = options.cutoff > 0.0
                        ? "given (‹cutoff›)"
                        : "from the data: of 5, 10, 20, ... x the motion frequency RMS(q')/(2 pi RMS(q)) up to the "
                          "decimated band 0.8 x rate / (2 x decimation), the highest unless a lower one leaves a residual 5 % "
                          "smaller";
  if (!options.sensitivity) {
    DecideAxisDetermined(out.fit, options.max_relative_std, out.rate_variation);
    return out;
  }
  // The same fit at half and at twice the cutoff (twice: if below Nyquist).
  for (const double factor : {0.5, 2.0}) {
    AxisFitOptions other = central;
    other.cutoff = factor * central.cutoff;
    other.per_log = false;
    if (!(other.cutoff <= AxisHighestCutoff(logs))) continue;
    EstimateSet entry{fmt::format("cutoff {:.3g} Hz", other.cutoff), {}, "", other.cutoff};
    try {
      entry.estimates = FitAtCutoff(logs, start, other, &cache, AtCutoff::kScore).fit.estimates;
    } catch (const std::exception& e) {
      entry.failure = e.what();
    }
    out.fit.sensitivity.push_back(std::move(entry));
  }
  // Warn where the processing moves an estimate by more than 2 of its std
  // and by more than 5 % (clean logs move by a fraction of a percent).
  // With a measured rate already used, only the acceleration (differentiated
  // qd) depends on the cutoff: do not suggest what was given.
  const bool rate_measured = std::all_of(logs.begin(), logs.end(), [](const AxisLog& l) { return !l.rate.empty(); });
  const std::string advice = rate_measured ? std::string("the measured rate qd is used and differentiated once; check "
                                                         "the cutoff with ‹cutoff›, or ") + kAxisOutputErrorAdvice
                                           : std::string("try a measured rate qd, or check the cutoff with ‹cutoff›");
  for (auto& w : ProcessingWarnings(out.fit, out.cutoff, advice)) {
    out.fit.warnings.push_back(std::move(w));
  }
  WidenForProcessing(out.fit, out.cutoff);
  // The timing's uncertainty in the covariance, when the data chose it.
  AddTimingCovariance(logs, start, central, timing, &cache, out.fit);
  DecideAxisDetermined(out.fit, options.max_relative_std, out.rate_variation);
  return out;
}

std::vector<ResolvedAxisTerm> ResolveAxisTerms(const AxisSection& start, const std::vector<std::string>& free) {
  // A linear axis has no angle: its weight is a constant force, the offset.
  if (start.linear) {
    for (const auto member : {&AxisParameters::gravity_cos, &AxisParameters::gravity_sin}) {
      const std::string key = AxisKey(member);
      const auto given = SectionValue(*FindParameter(AxisParameterTable(), key), start);
      if (Contains(free, key)) {
        throw OptionError(fmt::format("‹free› {}: a linear axis (axis.linear, ‹linear›) has no cos q / sin q "
                                      "gravity: its weight is a constant force, fitted as the offset",
                                      key));
      }
      if (given.value_or(0.0) != 0.0) {
        throw InputError(fmt::format("‹params›: axis.{} = {} on a linear axis: gravity there is a constant force, "
                                     "the offset; remove {}",
                                     key, *given, key));
      }
    }
  }
  // Parameters a free direction-dependent pair replaces (coulomb, viscous).
  std::vector<std::string> replaced;
  for (const auto& key : free) {
    const std::string original = AxisReplacedBy(key);
    if (original.empty()) continue;
    if (Contains(free, original)) {
      throw OptionError(fmt::format("‹free›: {} and {} describe the same friction: give one or the other", original,
                                    key));
    }
    replaced.push_back(original);
  }
  // Both Coulomb directions span the offset where the axis never rests: an
  // offset not given is then 0 (the fit refuses it by name if it is free).
  if (Contains(free, AxisKey(&AxisParameters::coulomb_pos)) && Contains(free, AxisKey(&AxisParameters::coulomb_neg))) {
    replaced.push_back(AxisKey(&AxisParameters::offset));
  }
  std::vector<ResolvedAxisTerm> terms;
  std::vector<const ParameterSpec*> needed;
  for (std::size_t j = 0; j < AxisParameterCount(); ++j) {
    const ParameterSpec& spec = AxisTermRow(j).spec;
    const std::optional<double> value = SectionValue(AxisTermRow(j), start);
    const bool is_free = Contains(free, spec.key);
    if (!is_free && !value && spec.default_free && j != 0 && !Contains(replaced, spec.key)) needed.push_back(&spec);
    // A fixed inertia, a gravity or direction term, or a replaced friction
    // term that is not given counts as 0; the adequacy checks say when the
    // residuals contradict that.
    const double v = is_free ? std::max(spec.lower_bound, value.value_or(0.0)) : value.value_or(0.0);
    terms.push_back({spec.key, j, is_free, v});
  }
  if (!needed.empty()) {
    throw MissingValuesError("‹params›", "axis", needed, "(fixed in this fit)", " (or name them in ‹free›)");
  }
  return terms;
}

AxisFitOutput FitAxisAtCutoff(const std::vector<AxisLog>& given, const AxisSection& start, const AxisFitOptions& options) {
  std::vector<AxisLog> storage;
  const std::vector<AxisLog>& logs = UniformAxisLogs(given, storage, nullptr);
  AxisFitOptions o = options;
  std::string rule;
  o.decimation = AxisDecimationFor(logs, options.decimation, &rule);
  AxisFitOutput out = FitAtCutoff(logs, start, o, nullptr, AtCutoff::kFull);
  DecideAxisDetermined(out.fit, options.max_relative_std, out.rate_variation);
  out.decimation = o.decimation;
  out.decimation_rule = rule;
  return out;
}

namespace {

// The free linear terms and the fixed values (a nonlinear term refused:
// inverse dynamics neither fits nor subtracts it); the adequacy checks'
// diagnostic columns held at 0.
void AxisDesign(const AxisSection& start, const std::vector<std::string>& free, std::vector<FitParameter>& parameters,
                std::map<std::string, double>& fixed) {
  for (const auto& term : ResolveAxisTerms(start, free)) {
    if (term.index >= AxisLinearCount()) {
      const AxisTermParameter& owner = AxisParameterTerm(term.index);
      if (term.free) {
        throw OptionError(fmt::format("‹free› {}: the {} term is nonlinear in the rate: fit it with ‹method› oe",
                                      term.key, owner.term->name()));
      }
      if (owner.row == 0 && term.value != 0.0) {
        throw InputError(fmt::format("‹params›: axis.{} = {}: the {} term needs ‹method› oe (inverse dynamics would "
                                     "ignore it)", term.key, term.value, owner.term->name()));
      }
      continue;
    }
    if (term.free) {
      parameters.push_back({term.key, term.value, AxisParameterTable()[term.index].spec.lower_bound, 0.0});
    }
    fixed[term.key] = term.value;
  }
  for (const char* name : {kAxisAbsRateColumn, kAxisTimeColumn}) fixed[name] = 0.0;
}

// The rows at the options' cutoff: from the cache, or built (and cached
// when small enough).
std::shared_ptr<const AxisRows> RowsAtCutoff(const std::vector<AxisLog>& logs, const AxisFitOptions& options,
                                             AxisReach reach, AxisRowCache* cache) {
  std::shared_ptr<const AxisRows> built;
  const double delay = options.torque_timing == AxisTorqueTiming::kDelayed ? options.torque_delay : 0.0;
  const auto key = std::make_tuple(options.cutoff, options.torque_timing, delay,
                                   AxisRowReaches(logs, options.cutoff, options.decimation, reach));
  if (cache != nullptr) {
    const auto found = cache->find(key);
    if (found != cache->end()) built = found->second;
  }
  if (!built) {
    const std::vector<std::string> column_names = AxisRowColumnNames();
    built = std::make_shared<const AxisRows>(
        BuildAxisRows(logs, options.cutoff, options.decimation, options.min_rate_fraction, column_names,
                      options.torque_timing, reach, delay));
    if (cache != nullptr && built->regression.rows() * column_names.size() * sizeof(double) <= kCachedRowBytes) {
      (*cache)[key] = built;
    }
  }
  return built;
}

// Acceleration content: with a free inertia the decimated accelerations
// must matter next to the rates (RMS(q'') / RMS(q') in 1/s); a constant-rate
// log has only quantisation noise there and identifies friction only.
double AccelerationContent(const LinearRegression& regression) {
  double acceleration_square = 0.0, rate_square = 0.0;
  for (std::size_t r = 0; r < regression.rows(); ++r) {
    acceleration_square += std::pow(regression.at(r, 0), 2);
    rate_square += std::pow(regression.at(r, 1), 2);
  }
  return rate_square > 0.0 ? std::sqrt(acceleration_square / rate_square) : 0.0;
}

// How much the rate varies within the logs: sqrt(sum (q' - mean_log q')^2 /
// sum q'^2) over the rows (0 where every log holds one rate).
double RateVariation(const LinearRegression& regression, const std::vector<int>& log_index) {
  std::map<int, std::pair<double, int>> sums;  // per log: sum of q', rows
  for (std::size_t r = 0; r < regression.rows(); ++r) {
    auto& s = sums[r < log_index.size() ? log_index[r] : 0];
    s.first += regression.at(r, 1);
    ++s.second;
  }
  double spread = 0.0, square = 0.0;
  for (std::size_t r = 0; r < regression.rows(); ++r) {
    const auto& s = sums[r < log_index.size() ? log_index[r] : 0];
    const double v = regression.at(r, 1);
    spread += std::pow(v - s.first / s.second, 2);
    square += v * v;
  }
  return square > 0.0 ? std::sqrt(spread / square) : 0.0;
}

AxisFitOutput FitAtCutoff(const std::vector<AxisLog>& logs, const AxisSection& start, const AxisFitOptions& options,
                          AxisRowCache* cache, AtCutoff extent, AxisReach reach) {
  if (logs.empty()) throw OptionError("no logs given");
  CheckFreeNames(AxisParameterTable(), "axis", options.free);
  RequireValid(options);
  std::vector<FitParameter> parameters;
  std::map<std::string, double> fixed;
  AxisDesign(start, options.free, parameters, fixed);
  const int p = static_cast<int>(parameters.size());

  AxisFitOutput out;
  const std::shared_ptr<const AxisRows> built = RowsAtCutoff(logs, options, reach, cache);
  const AxisRows& rows = *built;
  const LinearRegression& regression = rows.regression;
  out.method = rows.method;
  out.cutoff = options.cutoff;
  out.torque_timing = options.torque_timing;
  out.torque_delay = options.torque_delay;
  out.time = rows.time;
  out.measured = rows.measured;
  out.log_index = rows.log_index;
  const int rows_used = static_cast<int>(regression.rows());
  if (rows_used <= p) {
    throw IdentificationError(fmt::format("{} usable samples after decimation cannot determine {} parameters (the logs "
                                          "barely move or are too short)", rows_used, p));
  }
  out.acceleration_content = AccelerationContent(regression);
  out.rate_variation = RateVariation(regression, out.log_index);
  FitOptions fit_options = options.fit;
  if (!fit_options.advice) {
    fit_options.advice = [](const std::vector<std::string>& involved) -> std::string {
      if (Contains(involved, AxisKey(&AxisParameters::inertia))) {
        return "the log has no acceleration content: fit friction alone with ‹free› viscous,coulomb,offset";
      }
      if (Contains(involved, AxisKey(&AxisParameters::coulomb)) && Contains(involved, AxisKey(&AxisParameters::offset))) {
        return "coulomb and offset need motion in both directions";
      }
      return "";
    };
  }
  out.fit = regression.Fit(parameters, fixed, fit_options);
  std::map<std::string, double> fitted = fixed;
  for (const auto& e : out.fit.estimates) fitted[e.name] = e.value;
  for (std::size_t j = 0; j < AxisLinearCount(); ++j) ModelValue(Column(j), out.params) = fitted[Column(j).spec.key];
  std::vector<std::string> free_names;
  for (const auto& e : out.fit.estimates) free_names.push_back(e.name);
  if (extent == AtCutoff::kFull) out.fit.warnings = CheckAxisAdequacy(regression, out.fit, free_names, fitted, start.linear);
  if (extent == AtCutoff::kFull && options.per_log && logs.size() > 1) {
    AxisFitOptions alone = options;
    alone.per_log = false;
    AddPerLogFits(out.fit, LogLabels(logs), [&](std::size_t i) { return FitAxis({logs[i]}, start, alone).fit.estimates; });
  }
  // Whether the data determine each estimate is decided on the fit's final
  // covariance (DecideAxisDetermined, by FitAxis): a candidate cutoff or an
  // alternative processing (kScore) gives its estimates as they are, so
  // that their spread enters the intervals even where one is at its bound.
  // Model at the used samples and the relative error.
  double residual_norm = 0.0, force_norm = 0.0;
  out.model = regression.Predict(fitted);
  for (std::size_t r = 0; r < regression.rows(); ++r) {
    residual_norm += std::pow(out.measured[r] - out.model[r], 2);
    force_norm += std::pow(out.measured[r], 2);
  }
  out.relative_error_percent = force_norm > 0.0 ? 100.0 * std::sqrt(residual_norm / force_norm) : 0.0;
  out.samples_used = rows_used;
  return out;
}

}  // namespace

}  // namespace driveid
