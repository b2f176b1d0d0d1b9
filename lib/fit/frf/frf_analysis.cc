#include "fit/frf/frf_analysis.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"
#include "signal/butterworth.h"
#include "signal/resample.h"

namespace driveid {

bool FrfOptions::IsValid(std::string* error) const { return OptionCheck(error).Nested(estimate).Nested(two_mass); }
namespace {

// The mean rotation frequency [Hz] of the motor output (a rate or an angle,
// taken as radians), 0 for an acceleration: its harmonics are disturbance
// lines (unbalance, cogging, gear meshing), not modes.
double MeanRotation(const std::vector<FrfSignals>& logs, ResponseQuantity quantity) {
  double turns = 0.0, span = 0.0;
  for (const auto& log : logs) {
    const double duration = log.time.back() - log.time.front();
    if (!(duration > 0.0)) continue;
    if (quantity == ResponseQuantity::kPosition) {
      turns += std::abs(log.output.back() - log.output.front()) / (2.0 * M_PI);
    } else if (quantity == ResponseQuantity::kRate) {
      double mean = 0.0;
      for (double v : log.output) mean += v / static_cast<double>(log.output.size());
      turns += std::abs(mean) * duration / (2.0 * M_PI);
    }
    span += duration;
  }
  return span > 0.0 ? turns / span : 0.0;
}

// Features read from out.motor and, if asked, the two-mass fit.
void FitResponse(FrfResult& out, const JointSection& start, const FrfOptions& options, double hold_rate,
                 double rotation_hz) {
  const ResponseData motor_data{out.motor.frequency, out.motor.response, out.motor.coherence,
                                out.motor.log_magnitude_std, out.motor.phase_std, out.motor.excitation,
                                0.5 * out.rate, rotation_hz};
  TwoMassFitOptions fit_options = options.two_mass;
  fit_options.hold_rate = hold_rate;
  const ResponseBand band = fit_options.Band();
  if (out.rate > 0.0 && band.high > 0.0 && !(band.low < 0.5 * out.rate)) {
    throw OptionError(fmt::format("‹band› {:g},{:g}: at or above the logs' Nyquist frequency {:g} Hz (half the {:g} Hz "
                                  "rate): nothing was measured there",
                                  band.low, band.high, 0.5 * out.rate, out.rate));
  }
  ResponseData read_data = motor_data;
  if (out.motor.std_scale_unknown) {  // the read's std from its own scatter
    read_data.log_magnitude_std.clear();
    read_data.phase_std.clear();
  }
  out.read = ReadResponseFeatures(read_data, fit_options.motor_output, band);
  if (out.read.bins < kMinResponseBins) {
    // An empty frf section with exit 0 would pass for a measurement.
    throw IdentificationError(fmt::format(
        "no frequency response to read: {} usable bin{} (at least {}) {}, at {:.4g} Hz resolution: {}",
        out.read.bins, out.read.bins == 1 ? "" : "s", kMinResponseBins,
        band.high > 0.0 ? fmt::format("in ‹band› {:g},{:g}", band.low, band.high) : "where the excitation is coherent",
        out.motor.resolution,
        band.high > 0.0 ? "widen the band, or check it lies where the excitation is"
                        : "the output does not follow the input (a zero or constant channel?), or the excitation is too weak"));
  }
  out.notes.insert(out.notes.end(), out.read.notes.begin(), out.read.notes.end());
  if (!options.fit) out.warnings.insert(out.warnings.end(), out.read.warnings.begin(), out.read.warnings.end());
  if (options.fit) {
    std::optional<ResponseData> link_data;
    if (out.link) {
      link_data = ResponseData{out.link->frequency, out.link->response, out.link->coherence,
                               out.link->log_magnitude_std, out.link->phase_std, out.link->excitation,
                               0.5 * out.rate, rotation_hz};
    }
    out.fit = FitTwoMassResponse(motor_data, link_data ? &*link_data : nullptr, start, fit_options);
    // The fit core has added its low-fit warnings already; the response's own join them.
    out.fit->fit.warnings.insert(out.fit->fit.warnings.end(), out.warnings.begin(), out.warnings.end());
  }
}

}  // namespace

FrequencyResponseSection FrfResult::Section() const {
  FrequencyResponseSection s;
  const FrequencyEstimate& r = fit ? fit->resonance : read.resonance;
  const FrequencyEstimate& a = fit ? fit->antiresonance : read.antiresonance;
  if (r.value > 0.0) {
    s.resonance_hz = r.value;
    s.resonance_hz_std = r.standard_error;
  }
  if (a.value > 0.0) {
    s.antiresonance_hz = a.value;
    s.antiresonance_hz_std = a.standard_error;
  }
  const double low = fit ? fit->band_low : read.band_low, high = fit ? fit->band_high : read.band_high;
  if (high > 0.0) s.band_hz = std::array<double, 2>{low, high};
  s.method = motor.description + (fit ? "; two-mass fit" : "; read from the response");
  return s;
}

FrfResult AnalyseFrequencyResponse(const std::vector<FrfSignals>& logs, const JointSection& start,
                                   const FrfOptions& options) {
  RequireValid(options);
  if (logs.empty()) throw OptionError("no logs given");
  FrfResult out;
  std::vector<FrequencyRecord> motor, link;
  const bool has_link = !logs.front().link.empty();
  for (const auto& log : logs) {
    if (log.time.size() < 32) throw InputError(fmt::format("{}: {} samples: too short for a frequency response", log.label, log.time.size()));
    if (log.link.empty() == has_link) {
      if (&log != &logs.front()) throw InputError(fmt::format("{}: the link signal is logged in some logs only", log.label));
    }
    double rate = ConstantRate(log.time, 1e-3);
    FrfSignals signals = log;
    if (rate == 0.0) {
      // Irregular time stamps: resampled at the mean rate (linear interpolation).
      const double span = log.time.back() - log.time.front();
      rate = static_cast<double>(log.time.size() - 1) / span;
      const std::size_t count = static_cast<std::size_t>(std::floor(span * rate)) + 1;
      double jitter = 0.0;
      for (std::size_t i = 1; i < log.time.size(); ++i) jitter = std::max(jitter, std::abs((log.time[i] - log.time[i - 1]) * rate - 1.0));
      for (auto* v : {&signals.input, &signals.output, &signals.reference, &signals.link}) {
        if (!v->empty()) *v = ResampleLinear(log.time, *v, rate, count);
      }
      out.notes.push_back(fmt::format("{}: time steps vary by up to {:.3g} % of the mean: resampled at {:.6g} Hz by "
                                      "linear interpolation",
                                      log.label, 100.0 * jitter, rate));
    }
    if (out.rate == 0.0) {
      out.rate = rate;
    } else if (std::abs(rate / out.rate - 1.0) > 1e-3) {
      throw InputError(fmt::format("{}: sampled at {:.6g} Hz, the first log at {:.6g} Hz: a response pools logs of one "
                                   "rate",
                                   log.label, rate, out.rate));
    }
    motor.push_back({signals.input, signals.output, signals.reference});
    if (has_link) link.push_back({signals.input, signals.link, signals.reference});
  }
  out.motor = EstimateFrequencyResponse(motor, out.rate, options.estimate);
  if (has_link) {
    FrequencyResponseOptions same = options.estimate;
    same.method = out.motor.method;
    same.resolution = out.motor.resolution;
    if (out.motor.method == FrequencyMethod::kPeriodic) same.period = 1.0 / out.motor.resolution;
    out.link = EstimateFrequencyResponse(link, out.rate, same);
  }
  if (!out.motor.closed_loop) {
    // Open-loop H1 is biased by feedback: a log whose input follows its
    // output (a loop closed around it) draws a warning.
    // Counted where the input is excited: elsewhere a low coherence says nothing about feedback.
    const auto& f = out.motor;
    const std::vector<char> excited_bins = ExcitedBins(f.excitation, f.coherence.size());
    int low_coherence = 0, excited = 0;
    for (std::size_t b = 0; b < f.coherence.size(); ++b) {
      if (!excited_bins[b]) continue;
      ++excited;
      low_coherence += f.coherence[b] < 0.5;
    }
    if (low_coherence > excited / 2) {
      out.warnings.push_back(fmt::format("coherence below 0.5 in {} of the {} excited bins: in closed loop give the "
                                         "injected excitation with ‹reference› (S_ry/S_ru is not biased by the feedback)",
                                         low_coherence, excited));
    }
  }
  FitResponse(out, start, options, options.hold ? out.rate : 0.0, MeanRotation(logs, options.two_mass.motor_output));
  return out;
}

namespace {
// A measured coherence of 1 would weigh its bin infinitely: clamped here.
constexpr double kMinMeasuredCoherence = 0.01, kMaxMeasuredCoherence = 0.999;
}  // namespace

FrfResult AnalyseMeasuredResponse(const MeasuredResponse& measured, const JointSection& start, const FrfOptions& options) {
  RequireValid(options);
  const std::size_t n = measured.frequency.size();
  if (n < 5) throw InputError(fmt::format("a measured response of {} bins: at least 5 are needed", n));
  FrfResult out;
  FrequencyResponse& r = out.motor;
  r.method = FrequencyMethod::kWelch;
  r.description = fmt::format("measured elsewhere ({} bins, read with ‹measured›)", n);
  for (std::size_t b = 0; b < n; ++b) {
    const double f = measured.frequency[b], m = measured.magnitude[b];
    if (!(f > 0.0) || !(m > 0.0) || !std::isfinite(m) || !std::isfinite(measured.phase[b])) {
      throw InputError(fmt::format("measured response, bin {} ({} Hz): frequency and magnitude must be positive and "
                                   "finite (magnitude {}, phase {} rad)",
                                   b + 1, f, m, measured.phase[b]));
    }
    if (!measured.coherence.empty() && !(measured.coherence[b] >= 0.0 && measured.coherence[b] <= 1.0)) {
      throw InputError(fmt::format("measured response, bin {} ({} Hz): coherence {}: a coherence lies in 0 .. 1", b + 1,
                                   f, measured.coherence[b]));
    }
    r.frequency.push_back(f);
    r.response.push_back(std::polar(m, measured.phase[b]));
    r.coherence.push_back(measured.coherence.empty() ? 1.0 : measured.coherence[b]);
  }
  r.resolution = n > 1 ? (r.frequency.back() - r.frequency.front()) / static_cast<double>(n - 1) : 0.0;
  if (measured.coherence.empty()) {
    out.notes.push_back("no std with the measured response: every bin weighs the same and the fit estimates the "
                        "residual scale; the model is continuous (the measurement's sampling is unknown)");
  } else {
    // The coherence sets each bin's relative std (Bendat & Piersol,
    // eps = sqrt(1 - g^2) / (|g| sqrt(2 n)) with n, the averages, unknown and
    // the same for all: the fit estimates the scale from the residuals).
    for (double g2 : r.coherence) {
      const double g = std::min(std::max(g2, kMinMeasuredCoherence), kMaxMeasuredCoherence);
      const double relative = std::sqrt((1.0 - g) / g);
      r.log_magnitude_std.push_back(relative);
      r.phase_std.push_back(relative);
    }
    r.std_scale_unknown = true;
    out.notes.push_back(fmt::format(
        "the measured coherence weighs the bins: std of ln|H| and of the phase proportional to sqrt(1 - g^2) / g "
        "(coherence taken within {} .. {}), the scale from the residuals; the model is continuous (the measurement's "
        "sampling is unknown)",
        kMinMeasuredCoherence, kMaxMeasuredCoherence));
  }
  FitResponse(out, start, options, 0.0, 0.0);
  return out;
}

}  // namespace driveid
