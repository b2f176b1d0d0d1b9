#include "fit/axis/axis_rows.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/fit_result.h"
#include "models/axis.h"
#include "models/axis_term.h"
#include "signal/butterworth.h"
#include "signal/local_polynomial.h"

namespace driveid {
namespace {

// The mean rate of the stamps [Hz] (0 for fewer than 2 or no span).
double MeanRate(const std::vector<double>& time) {
  return time.size() < 2 || !(time.back() > time.front())
             ? 0.0
             : static_cast<double>(time.size() - 1) / (time.back() - time.front());
}

}  // namespace

AxisDerivatives DifferentiateAxisLog(const AxisLog& log, double cutoff_request, AxisPositionFilter filter) {
  AxisDerivatives d;
  const std::size_t n = log.time.size();
  d.rate_hz = ConstantRate(log.time);
  d.rate.assign(n, 0.0);
  d.acceleration.assign(n, 0.0);
  d.valid.assign(n, 0);
  if (d.rate_hz > 0.0) {
    const double cutoff = cutoff_request > 0.0 ? cutoff_request : d.rate_hz / 40.0;
    if (!(cutoff < 0.5 * d.rate_hz)) {
      throw OptionError(fmt::format("‹cutoff› = {}: violated constraint: below half the sampling rate {} Hz", cutoff,
                                    d.rate_hz));
    }
    const double dt = 1.0 / d.rate_hz;
    const auto low_pass = [&](const std::vector<double>& x) {
      return filter == AxisPositionFilter::kFlat ? FlatZeroPhaseLowPass(x, cutoff, d.rate_hz)
                                                 : ZeroPhaseLowPass(x, cutoff, d.rate_hz);
    };
    if (!log.rate.empty()) {
      // A measured rate: filtered, and differentiated once for q''.
      const std::vector<double> v = low_pass(log.rate);
      for (std::size_t k = 1; k + 1 < n; ++k) {
        d.rate[k] = v[k];
        d.acceleration[k] = (v[k + 1] - v[k - 1]) / (2.0 * dt);
        d.valid[k] = 1;
      }
      return d;
    }
    const std::vector<double> q = low_pass(log.position);
    for (std::size_t k = 1; k + 1 < n; ++k) {
      d.rate[k] = (q[k + 1] - q[k - 1]) / (2.0 * dt);
      d.acceleration[k] = (q[k + 1] - 2.0 * q[k] + q[k - 1]) / (dt * dt);
      d.valid[k] = 1;
    }
  } else {
    // Irregular sampling: local quadratic fits on the time stamps.
    const double mean_rate = MeanRate(log.time);
    const double cutoff = cutoff_request > 0.0 ? cutoff_request : mean_rate / 40.0;
    if (!log.rate.empty()) {
      const SignalDerivatives s = EstimateDerivatives(log.time, log.rate, 0.5 / cutoff);
      d.rate = s.value;
      d.acceleration = s.rate;
      d.valid = s.valid;
    } else {
      const SignalDerivatives s = EstimateDerivatives(log.time, log.position, 0.5 / cutoff);
      d.rate = s.rate;
      d.acceleration = s.acceleration;
      d.valid = s.valid;
    }
  }
  return d;
}

// (axis_rows.h) The logs' motion frequency f_m = RMS(q') / (2 pi RMS(q - linear trend))
// [Hz] (the largest over the logs): for q = A sin(2 pi f t) exactly f.
// Rates come from a first differentiation at the sampling rate / 40.
double AxisMotionFrequency(const std::vector<AxisLog>& logs) {
  double largest = 0.0;
  for (const auto& log : logs) {
    if (log.time.size() < kMinAxisLogSamples) continue;
    const AxisDerivatives d = DifferentiateAxisLog(log, 0.0, AxisPositionFilter::kButterworth);
    const std::size_t n = log.time.size();
    // Least-squares line through q(t).
    double st = 0.0, sq = 0.0, stt = 0.0, stq = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      const double t = log.time[k] - log.time.front();
      st += t;
      sq += log.position[k];
      stt += t * t;
      stq += t * log.position[k];
    }
    const double nn = static_cast<double>(n);
    const double denominator = nn * stt - st * st;
    const double slope = denominator > 0.0 ? (nn * stq - st * sq) / denominator : 0.0;
    const double intercept = (sq - slope * st) / nn;
    double position_square = 0.0, rate_square = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      const double t = log.time[k] - log.time.front();
      position_square += std::pow(log.position[k] - intercept - slope * t, 2);
      if (d.valid[k]) rate_square += std::pow(d.rate[k], 2);
    }
    if (position_square > 0.0) largest = std::max(largest, std::sqrt(rate_square / position_square) / (2.0 * M_PI));
  }
  return largest;
}


double AxisSamplingRate(const std::vector<AxisLog>& logs) {
  double lowest = HUGE_VAL;
  for (const auto& log : logs) {
    if (log.time.size() < 2) continue;
    double rate = ConstantRate(log.time);
    if (!(rate > 0.0)) rate = static_cast<double>(log.time.size() - 1) / (log.time.back() - log.time.front());
    lowest = std::min(lowest, rate);
  }
  return lowest;
}

double AxisDecimatedBand(double rate, int decimation) { return 0.8 * rate / (2.0 * std::max(1, decimation)); }

double AxisHighestCutoff(const std::vector<AxisLog>& logs) {
  const bool irregular =
      std::any_of(logs.begin(), logs.end(), [](const AxisLog& log) { return !(ConstantRate(log.time) > 0.0); });
  return (irregular ? kAxisIrregularCutoffShare : 0.4) * AxisSamplingRate(logs);
}

std::vector<double> AxisCutoffCandidates(const std::vector<AxisLog>& logs, int decimation) {
  const double rate = AxisSamplingRate(logs);
  if (!std::isfinite(rate) || !(rate > 0.0)) return {};
  const double motion = AxisMotionFrequency(logs);
  if (!(motion > 0.0) || !std::isfinite(motion)) return {rate / 40.0};
  // No higher than the band the decimated samples keep (the parallel
  // decimation filter's cutoff): above it only noise would change.
  const double top = std::min(AxisDecimatedBand(rate, decimation), AxisHighestCutoff(logs));
  std::vector<double> candidates;
  for (double c = kCutoffPerMotionFrequency * motion; c < top && candidates.size() < 12; c *= 2.0) {
    candidates.push_back(c);
  }
  if (candidates.empty() || candidates.back() < top) candidates.push_back(top);
  return candidates;
}

double PickAxisCutoff(const std::vector<double>& candidates, const std::function<double(double)>& mean_square) {
  if (candidates.empty()) return 0.0;
  double best = candidates.back(), best_residual = HUGE_VAL;
  for (std::size_t i = candidates.size(); i-- > 0;) {
    const double residual = mean_square(candidates[i]);
    if (residual < (1.0 - kAxisLowerCutoffGain) * best_residual) {
      best_residual = residual;
      best = candidates[i];
    }
  }
  return best;
}

int AxisShortestReach(double rate, int decimation) {
  return (rate > 0.0 ? kAxisExclusionDecimations : kAxisExclusionDecimationsIrregular) * std::max(1, decimation);
}

int AxisRowReach(double rate, double cutoff, int decimation, AxisReach reach, double mean_rate) {
  const int reached =
      AxisExclusionReach(rate, reach == AxisReach::kAtBand ? AxisDecimatedBand(rate, decimation) : cutoff, decimation);
  if (rate > 0.0 || !(mean_rate > 0.0) || !std::isfinite(mean_rate)) return reached;
  const double position_cutoff = cutoff > 0.0 ? cutoff : mean_rate / 40.0;
  const int step = std::max(1, decimation);
  const int window = static_cast<int>(std::min(std::ceil(0.5 / position_cutoff * mean_rate) + 1.0, 1e6));
  return std::max(reached, (window + step - 1) / step * step);
}

std::vector<int> AxisRowReaches(const std::vector<AxisLog>& logs, double cutoff, int decimation, AxisReach reach) {
  std::vector<int> reaches;
  reaches.reserve(logs.size());
  for (const auto& log : logs) {
    reaches.push_back(AxisRowReach(ConstantRate(log.time), cutoff, decimation, reach, MeanRate(log.time)));
  }
  return reaches;
}

int AxisExclusionReach(double rate, double cutoff, int decimation) {
  const int step = std::max(1, decimation);
  if (!(rate > 0.0)) return AxisShortestReach(rate, step);
  const double band = AxisDecimatedBand(rate, step);
  const double position_cutoff = std::max(cutoff > 0.0 ? cutoff : rate / 40.0, kAxisExclusionLowestCutoff * band);
  // A unit step in the middle of a record long enough for both filters to
  // settle (their time constants are ~ 1 / (2 pi cutoff)).
  const double slowest = step > 1 ? std::min(position_cutoff, band) : position_cutoff;
  const std::size_t half =
      static_cast<std::size_t>(std::ceil(8.0 * rate / slowest)) + 4 * static_cast<std::size_t>(step);
  std::vector<double> x(2 * half + 1, 0.0);
  std::fill(x.begin() + static_cast<std::ptrdiff_t>(half), x.end(), 1.0);
  FlatZeroPhaseLowPassInPlace(x, position_cutoff, rate);
  if (step > 1) ZeroPhaseLowPassInPlace(x, band, rate);
  std::size_t distance = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double ideal = k >= half ? 1.0 : 0.0;
    if (std::abs(x[k] - ideal) > kAxisExclusionSettled) distance = std::max(distance, k >= half ? k - half : half - k);
  }
  const std::size_t whole = (distance + static_cast<std::size_t>(step) - 1) / static_cast<std::size_t>(step);
  return std::max(kAxisExclusionDecimations, static_cast<int>(whole)) * step;
}

std::vector<std::string> AxisRowColumnNames() {
  std::vector<std::string> names;
  for (std::size_t j = 0; j < AxisLinearCount(); ++j) names.emplace_back(AxisTermRow(j).spec.key);
  names.emplace_back(kAxisAbsRateColumn);
  names.emplace_back(kAxisTimeColumn);
  return names;
}

const char* AxisTorqueTimingName(AxisTorqueTiming timing) {
  switch (timing) {
    case AxisTorqueTiming::kHeld: return "held";
    case AxisTorqueTiming::kFromData: return "auto";
    case AxisTorqueTiming::kDelayed: return "delay";
    case AxisTorqueTiming::kSampled: break;
  }
  return "sampled";
}

std::vector<std::string> AxisTorqueTimingNames(const std::vector<AxisTorqueTiming>& timings) {
  std::vector<std::string> names;
  for (const AxisTorqueTiming timing : timings) names.emplace_back(AxisTorqueTimingName(timing));
  return names;
}

AxisTorqueTiming AxisTorqueTimingFromName(const std::string& name) {
  const std::vector<AxisTorqueTiming> named = {AxisTorqueTiming::kSampled, AxisTorqueTiming::kHeld,
                                               AxisTorqueTiming::kFromData};
  for (const AxisTorqueTiming timing : named) {
    if (name == AxisTorqueTimingName(timing)) return timing;
  }
  throw OptionError(
      fmt::format("‹torque-timing› {}: not one of {}", name, fmt::join(AxisTorqueTimingNames(named), ", ")));
}

AxisTorqueTiming ParseAxisTorqueTiming(const std::string& text, double& delay) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (!text.empty() && end == text.c_str() + text.size() && std::isfinite(value)) {
    if (!(std::abs(value) <= kMaxTorqueDelay)) {
      throw OptionError(fmt::format("‹torque-timing› {}: a delay in samples from -1 to 1", text));
    }
    delay = value;
    return AxisTorqueTiming::kDelayed;
  }
  delay = 0.0;
  return AxisTorqueTimingFromName(text);
}

std::string DescribeAxisTorqueTiming(AxisTorqueTiming timing, double delay) {
  if (timing != AxisTorqueTiming::kDelayed) return AxisTorqueTimingName(timing);
  return fmt::format("delay {:+.3f} samples", delay);
}

std::vector<double> TimedAxisTorque(const std::vector<double>& torque, AxisTorqueTiming timing) {
  if (timing == AxisTorqueTiming::kFromData) {
    throw OptionError("‹torque-timing› auto: the fit chooses the timing before it builds rows");
  }
  std::vector<double> out = torque;
  if (timing == AxisTorqueTiming::kHeld || timing == AxisTorqueTiming::kDelayed) {
    for (std::size_t k = 1; k < torque.size(); ++k) out[k] = 0.5 * (torque[k - 1] + torque[k]);
  }
  return out;
}

namespace {

// column at k + shift (|shift| <= 1.5 samples), linear between neighbours,
// held beyond the ends.
void ShiftColumn(std::vector<double>& column, double shift) {
  if (shift == 0.0 || column.size() < 2) return;
  const std::vector<double> in = column;
  const auto n = static_cast<long>(in.size());
  const long whole = static_cast<long>(std::floor(shift));
  const double fraction = shift - static_cast<double>(whole);
  for (long k = 0; k < n; ++k) {
    const long a = std::clamp(k + whole, 0L, n - 1), b = std::clamp(k + whole + 1, 0L, n - 1);
    column[static_cast<std::size_t>(k)] =
        (1.0 - fraction) * in[static_cast<std::size_t>(a)] + fraction * in[static_cast<std::size_t>(b)];
  }
}

// Every `decimation`-th sample more than `reach` samples from any slow one
// and more than reach + 2 from the ends (the filters' start-up).
std::vector<std::size_t> ClearSamples(const std::vector<char>& slow, std::size_t reach, int decimation) {
  const std::size_t n = slow.size();
  std::vector<char> clear(n, 1);
  std::size_t last_slow = 0;
  bool seen = false;
  for (std::size_t k = 0; k < n; ++k) {
    if (slow[k]) {
      seen = true;
      last_slow = k;
    }
    if (seen && k - last_slow <= reach) clear[k] = 0;
  }
  seen = false;
  for (std::size_t k = n; k-- > 0;) {
    if (slow[k]) {
      seen = true;
      last_slow = k;
    }
    if (seen && last_slow - k <= reach) clear[k] = 0;
  }
  const std::size_t margin = reach + 2;
  std::vector<std::size_t> kept;
  for (std::size_t k = margin; k + margin < n; k += static_cast<std::size_t>(decimation)) {
    if (clear[k]) kept.push_back(k);
  }
  return kept;
}

// The median length [samples] of the stretches of motion between two slow
// stretches (0 with fewer than two slow stretches).
std::size_t MedianMotionStretch(const std::vector<char>& slow) {
  std::vector<std::size_t> stretches;
  std::size_t k = 0;
  const std::size_t n = slow.size();
  while (k < n && !slow[k]) ++k;  // motion before the first slow stretch is not between two
  while (k < n) {
    while (k < n && slow[k]) ++k;
    const std::size_t from = k;
    while (k < n && !slow[k]) ++k;
    if (k < n) stretches.push_back(k - from);
  }
  if (stretches.empty()) return 0;
  std::nth_element(stretches.begin(), stretches.begin() + static_cast<std::ptrdiff_t>(stretches.size() / 2),
                   stretches.end());
  return stretches[stretches.size() / 2];
}

// For each sample the nearest one whose derivatives are valid (itself if
// valid; 0 when none is).
std::vector<std::size_t> NearestValid(const std::vector<char>& valid) {
  const std::size_t n = valid.size();
  std::vector<std::size_t> nearest(n, n);
  std::size_t last = n;
  for (std::size_t k = 0; k < n; ++k) {
    if (valid[k]) last = k;
    nearest[k] = last;
  }
  last = n;
  for (std::size_t k = n; k-- > 0;) {
    if (valid[k]) last = k;
    if (last < n && (nearest[k] == n || last - k < k - nearest[k])) nearest[k] = last;
  }
  for (std::size_t& k : nearest) k = k == n ? 0 : k;
  return nearest;
}

}  // namespace

AxisRows BuildAxisRows(const std::vector<AxisLog>& logs, double cutoff, int decimation, double min_rate_fraction,
                       const std::vector<std::string>& column_names, AxisTorqueTiming timing, AxisReach reach_at,
                       double torque_delay) {
  if (timing == AxisTorqueTiming::kDelayed && !(std::abs(torque_delay) <= kMaxTorqueDelay)) {
    throw OptionError(fmt::format("torque delay {} samples: from -1 to 1", torque_delay));
  }
  const double shift = timing == AxisTorqueTiming::kDelayed ? torque_delay - 0.5 : 0.0;
  AxisRows out{LinearRegression(column_names), {}, {}, {}, ""};
  LinearRegression& regression = out.regression;
  for (std::size_t i = 0; i < logs.size(); ++i) {
    const AxisLog& log = logs[i];
    if (log.time.size() < kMinAxisLogSamples) throw InputError(fmt::format("{}: {} samples: too few for IDIM-LS", log.path, log.time.size()));
    const AxisDerivatives d = DifferentiateAxisLog(log, cutoff);
    out.method = d.rate_hz > 0.0 ? "IDIM-LS: sharpened Butterworth zero-phase, central differences, parallel decimation"
                                 : "IDIM-LS on irregular samples: local-polynomial rates, subsampling";
    if (!log.rate.empty()) out.method += "; measured rate qd (q'' from it)";
    if (timing == AxisTorqueTiming::kHeld) out.method += "; torque held per sample (rows average u_(k-1), u_k)";
    if (timing == AxisTorqueTiming::kDelayed) {
      out.method += fmt::format("; torque acting {:+.3f} samples after its stamp (rows average u_(k-1), u_k)",
                                torque_delay);
    }
    const std::size_t n = log.time.size();
    double max_rate = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      if (d.valid[k]) max_rate = std::max(max_rate, std::abs(d.rate[k]));
    }
    const double min_rate = min_rate_fraction * max_rate;
    // The sample whose derivatives stand for k: an invalid one (an end the
    // differentiator's window does not cover: one sample at a constant rate,
    // half a local-polynomial window on irregular stamps; or a sample in a
    // gap) holds the nearest valid one's. The invalid stretches at the ends
    // count as slow, so that rows keep the reach from them; an invalid
    // sample inside is no row.
    const std::vector<std::size_t> nearest = NearestValid(d.valid);
    const auto derived = [&](std::size_t k) { return nearest[k]; };
    std::vector<char> slow(n, 0);
    for (std::size_t k = 0; k < n; ++k) slow[k] = std::abs(d.rate[derived(k)]) < min_rate;
    for (std::size_t k = 0; k < n && !d.valid[k]; ++k) slow[k] = 1;
    for (std::size_t k = n; k-- > 0 && !d.valid[k];) slow[k] = 1;
    // A kept sample must be clear of slow samples by the filters' reach,
    // but the reach takes at most kAxisExclusionShareOfMotion of a typical
    // stretch of motion from each end (no less than the shortest reach).
    int reach = AxisRowReach(d.rate_hz, cutoff, decimation, reach_at, MeanRate(log.time));
    const std::size_t stretch = MedianMotionStretch(slow);
    if (stretch > 0) {
      const int step = std::max(1, decimation);
      const int share = static_cast<int>(kAxisExclusionShareOfMotion * static_cast<double>(stretch)) / step * step;
      reach = std::min(reach, std::max(AxisShortestReach(d.rate_hz, step), share));
    }
    std::vector<std::size_t> kept = ClearSamples(slow, static_cast<std::size_t>(std::max(1, reach)), decimation);
    kept.erase(std::remove_if(kept.begin(), kept.end(), [&](std::size_t k) { return !d.valid[k]; }), kept.end());
    // Full-rate columns, one at a time (memory: one column besides the log):
    // the model's regressors (CalcAxisRegressors), then |q'| and t - t_mid.
    // Low-passed before decimation.
    const bool filtered = d.rate_hz > 0.0 && decimation > 1;
    const double band = AxisDecimatedBand(d.rate_hz, decimation);
    const std::size_t linear = AxisLinearCount(), width = linear + 2;
    std::vector<double> rows(kept.size() * width), column(n);
    const double middle_time = 0.5 * (log.time.front() + log.time.back());
    for (std::size_t c = 0; c < width; ++c) {
      // Only terms that are not mode-affine (gravity) depend on q (the
      // trigonometry is most of the time).
      const bool trigonometric = c < linear && !AxisParameterTerm(c).term->mode_affine();
      for (std::size_t k = 0; k < n; ++k) {
        const std::size_t m = derived(k);
        const double position = trigonometric ? log.position[k] : 0.0;
        column[k] = c < linear   ? CalcAxisRegressors(position, d.rate[m], d.acceleration[m])[c]
                    : c == linear ? std::abs(d.rate[m])
                                  : log.time[k] - middle_time;
      }
      if (c < linear) ShiftColumn(column, shift);
      if (filtered) ZeroPhaseLowPassInPlace(column, band, d.rate_hz);
      for (std::size_t r = 0; r < kept.size(); ++r) rows[r * width + c] = column[kept[r]];
    }
    column = TimedAxisTorque(log.force, timing);
    if (filtered) ZeroPhaseLowPassInPlace(column, band, d.rate_hz);
    regression.BeginChannel(log.path + kTorqueChannelSuffix);
    std::vector<double> row(width);
    for (std::size_t r = 0; r < kept.size(); ++r) {
      std::copy_n(rows.begin() + static_cast<std::ptrdiff_t>(r * width), width, row.begin());
      regression.AddRow(row, column[kept[r]]);
      out.time.push_back(log.time[kept[r]]);
      out.measured.push_back(column[kept[r]]);
      out.log_index.push_back(static_cast<int>(i));
    }
  }
  return out;
}

}  // namespace driveid
