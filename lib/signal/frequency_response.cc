#include "signal/frequency_response.h"
#include "signal/lagged_products.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <unsupported/Eigen/FFT>

#include "core/errors.h"
#include "core/option_check.h"
#include "core/order_statistics.h"

namespace driveid {

bool FrequencyResponseOptions::IsValid(std::string* error) const {
  return OptionCheck(error)
      .Require(NotNegative(resolution), "‹resolution›", resolution, "resolution >= 0 Hz (0: from the records)")
      .Require(NotNegative(period), "‹period›", period, "period >= 0 s (0: detected)");
}
namespace {

using Complex = std::complex<double>;

constexpr int kMinAverages = 4;
constexpr std::size_t kMinPeriodSamples = 4;  // shortest period read, given or detected
// A lag is the period when the signal shifted by it (and by twice it, where
// the record holds three periods) differs from itself by at most this rms
// fraction of the signal's rms: a repeating excitation under measurement
// noise of up to about 20 % of its rms (a logged torque's) passes, a sweep
// or a signal that only resembles itself does not.
constexpr double kPeriodTolerance = 0.3;

// Largest prime factor of n (n >= 1).
std::size_t LargestPrimeFactor(std::size_t n) {
  std::size_t largest = 1;
  for (std::size_t p = 2; p * p <= n; ++p) {
    while (n % p == 0) {
      largest = p;
      n /= p;
    }
  }
  return n > 1 ? n : largest;
}

// DFT of real x, all n bins, in O(n log n) for any n: Eigen's FFT (kissfft)
// where n has only small prime factors (it is O(n p) in a prime factor p),
// else Bluestein's chirp-z transform through power-of-two FFTs:
// X_k = conj(w_k) sum_j (x_j conj(w_j)) w_(k-j), w_j = exp(i pi j^2 / n).
std::vector<Complex> Dft(Eigen::FFT<double>& fft, const std::vector<double>& x) {
  const std::size_t n = x.size();
  std::vector<Complex> out;
  if (n == 0) return out;
  if (n == 1) return {Complex(x[0], 0.0)};  // kissfft's plan for one point indexes an empty buffer
  if (LargestPrimeFactor(n) <= 7) {
    fft.ClearFlag(Eigen::FFT<double>::HalfSpectrum);
    fft.fwd(out, x);
    return out;
  }
  std::size_t m = 1;
  while (m < 2 * n - 1) m *= 2;
  std::vector<Complex> chirp(n);
  for (std::size_t j = 0; j < n; ++j) {
    // j^2 mod 2n keeps the angle exact for large j (j < n < 2^32: j^2 fits in 64 bits).
    const auto square = static_cast<double>((static_cast<std::uint64_t>(j) * j) % (2 * static_cast<std::uint64_t>(n)));
    chirp[j] = std::polar(1.0, M_PI * square / static_cast<double>(n));
  }
  std::vector<Complex> a(m, 0.0), b(m, 0.0), fa, fb, conv;
  for (std::size_t j = 0; j < n; ++j) a[j] = x[j] * std::conj(chirp[j]);
  b[0] = chirp[0];
  for (std::size_t j = 1; j < n; ++j) b[j] = b[m - j] = chirp[j];
  fft.fwd(fa, a);
  fft.fwd(fb, b);
  for (std::size_t k = 0; k < m; ++k) fa[k] *= fb[k];
  fft.inv(conv, fa);
  out.resize(n);
  for (std::size_t k = 0; k < n; ++k) out[k] = std::conj(chirp[k]) * conv[k];
  return out;
}

// Spectrum of x[begin, begin + n) after removing its least-squares line and
// multiplying by `window` (empty: rectangular); bins 0 .. n/2.
std::vector<Complex> SegmentSpectrum(Eigen::FFT<double>& fft, const std::vector<double>& x, std::size_t begin,
                                     std::size_t n, const std::vector<double>& window, bool detrend) {
  std::vector<double> segment(x.begin() + static_cast<std::ptrdiff_t>(begin),
                              x.begin() + static_cast<std::ptrdiff_t>(begin + n));
  if (detrend) {
    // Least-squares line over k = 0 .. n-1, centred.
    const double c = 0.5 * static_cast<double>(n - 1);
    double mean = 0.0, slope_num = 0.0, slope_den = 0.0;
    for (std::size_t k = 0; k < n; ++k) mean += segment[k];
    mean /= static_cast<double>(n);
    for (std::size_t k = 0; k < n; ++k) {
      const double dk = static_cast<double>(k) - c;
      slope_num += dk * (segment[k] - mean);
      slope_den += dk * dk;
    }
    const double slope = slope_den > 0.0 ? slope_num / slope_den : 0.0;
    for (std::size_t k = 0; k < n; ++k) segment[k] -= mean + slope * (static_cast<double>(k) - c);
  }
  if (!window.empty()) {
    for (std::size_t k = 0; k < n; ++k) segment[k] *= window[k];
  }
  std::vector<Complex> spectrum = Dft(fft, segment);
  spectrum.resize(n / 2 + 1);
  return spectrum;
}

void CheckRecords(const std::vector<FrequencyRecord>& records, bool& closed_loop) {
  if (records.empty()) throw InputError("no records");
  closed_loop = !records.front().reference.empty();
  for (const auto& r : records) {
    if (r.output.size() != r.input.size() || (!r.reference.empty() && r.reference.size() != r.input.size())) {
      throw InputError("the signals of a record differ in length");
    }
    if (r.reference.empty() == closed_loop) throw InputError("a reference is given for some records only");
    for (const auto* signal : {&r.input, &r.output, &r.reference}) {
      for (double v : *signal) {
        if (!std::isfinite(v)) throw InputError("a signal is not finite");
      }
    }
  }
}

// Sums over the Hann-windowed segments of n samples (50 % overlap) of the
// auto and cross spectra; x is the input u (open loop) or the reference r.
struct WelchSums {
  std::vector<double> sxx, suu, syy;
  std::vector<Complex> sxy, sxu;
  int averages = 0;
};
WelchSums SumSegments(const std::vector<FrequencyRecord>& records, std::size_t n, bool closed_loop) {
  std::vector<double> window(n);
  for (std::size_t k = 0; k < n; ++k) window[k] = 0.5 - 0.5 * std::cos(2.0 * M_PI * static_cast<double>(k) / static_cast<double>(n));
  const std::size_t bins = n / 2 + 1, step = n / 2;
  WelchSums s{std::vector<double>(bins, 0.0), std::vector<double>(bins, 0.0), std::vector<double>(bins, 0.0),
              std::vector<Complex>(bins, 0.0), std::vector<Complex>(bins, 0.0), 0};
  Eigen::FFT<double> fft;
  for (const auto& r : records) {
    for (std::size_t begin = 0; begin + n <= r.input.size(); begin += step) {
      ++s.averages;
      const auto u = SegmentSpectrum(fft, r.input, begin, n, window, true);
      const auto y = SegmentSpectrum(fft, r.output, begin, n, window, true);
      const auto x = closed_loop ? SegmentSpectrum(fft, r.reference, begin, n, window, true) : u;
      for (std::size_t b = 0; b < bins; ++b) {
        s.sxx[b] += std::norm(x[b]);
        s.suu[b] += std::norm(u[b]);
        s.syy[b] += std::norm(y[b]);
        s.sxy[b] += std::conj(x[b]) * y[b];
        s.sxu[b] += std::conj(x[b]) * u[b];
      }
    }
  }
  return s;
}

// The highest excited bin (DC left out).
std::size_t TopExcitedBin(const std::vector<double>& sxx) {
  const std::vector<double> without_dc(sxx.begin() + 1, sxx.end());
  const std::vector<char> excited = ExcitedBins(without_dc, without_dc.size());
  std::size_t top = 0;
  for (std::size_t b = 0; b < excited.size(); ++b) {
    if (excited[b]) top = b + 1;
  }
  return top;
}

// The default resolution resolves the excited band in at least this many
// bins (a sweep over a few Hz in a short log), down to kMinAverages averages.
constexpr std::size_t kMinExcitedBins = 32;

FrequencyResponse EstimateWelch(const std::vector<FrequencyRecord>& records, double rate, double resolution,
                                bool closed_loop) {
  std::size_t shortest = records.front().input.size();
  for (const auto& r : records) shortest = std::min(shortest, r.input.size());
  // Segment length: the resolution asked for, else about 8 averages over the
  // shortest record (K = 2 N / n - 1 with 50 % overlap).
  if (resolution > 0.0 && !(rate / resolution <= static_cast<double>(shortest))) {
    throw OptionError(fmt::format("‹resolution› {:.4g} Hz: finer than the shortest log ({} samples at {} Hz) can give; "
                                  "at least {:.4g} Hz",
                                  resolution, shortest, rate, rate * (kMinAverages + 1) / (2.0 * static_cast<double>(shortest))));
  }
  std::size_t n = resolution > 0.0 ? static_cast<std::size_t>(std::lround(rate / resolution))
                                   : static_cast<std::size_t>(2.0 * static_cast<double>(shortest) / 9.0);
  if (n < 16) {
    throw OptionError(fmt::format("‹resolution› {} Hz: segments of {} samples are too short (at {} Hz; at most {:.4g} Hz)",
                                  resolution, n, rate, rate / 16.0));
  }
  const std::size_t step = n / 2;
  int averages = 0;
  for (const auto& r : records) {
    if (r.input.size() >= n) averages += static_cast<int>((r.input.size() - n) / step + 1);
  }
  if (averages < kMinAverages) {
    throw OptionError(fmt::format("‹resolution› {:.4g} Hz: the logs give {} averages of {} samples; at least {} are "
                                  "needed (a coarser resolution, at least {:.4g} Hz here, or longer logs)",
                                  rate / static_cast<double>(n), averages, n, kMinAverages,
                                  rate * (kMinAverages + 1) / (2.0 * static_cast<double>(shortest))));
  }
  WelchSums sums = SumSegments(records, n, closed_loop);
  std::string finer;
  if (resolution == 0.0) {
    // A narrow excited band (a slow sweep) gets finer bins, down to the
    // fewest averages the estimate takes.
    const std::size_t top = TopExcitedBin(sums.sxx);
    const auto longest_n = static_cast<std::size_t>(2.0 * static_cast<double>(shortest) / (kMinAverages + 1));
    if (top > 0 && top < kMinExcitedBins && longest_n > n) {
      const std::size_t wanted = std::min(longest_n, n * kMinExcitedBins / top);
      if (wanted > n) {
        finer = fmt::format("; segments lengthened from {} samples to resolve the excited band (up to {:.4g} Hz) in "
                            "finer bins",
                            n, static_cast<double>(top) * rate / static_cast<double>(n));
        n = wanted;
        sums = SumSegments(records, n, closed_loop);
      }
    }
  }
  averages = sums.averages;
  const std::size_t bins = n / 2 + 1;
  const std::vector<double>&sxx = sums.sxx, &suu = sums.suu, &syy = sums.syy;
  const std::vector<Complex>&sxy = sums.sxy, &sxu = sums.sxu;
  // Hann with 50 % overlap: averages are correlated by 0.167 (Welch 1967).
  const double effective = averages / (1.0 + 2.0 * 0.167 * 0.167);
  FrequencyResponse out;
  out.averages = averages;
  out.resolution = rate / static_cast<double>(n);
  out.closed_loop = closed_loop;
  out.method = FrequencyMethod::kWelch;
  out.description = fmt::format("Welch {}, Hann window, 50 % overlap, {} averages of {} samples{}",
                                closed_loop ? "S_ry/S_ru (closed loop, reference)" : "H1 = S_uy/S_uu", averages, n,
                                finer);
  const auto relative_error2 = [&](double coherence) {
    return coherence > 0.0 ? (1.0 - coherence) / (2.0 * effective * coherence) : INFINITY;
  };
  for (std::size_t b = 1; b < bins; ++b) {
    if (!(sxx[b] > 0.0) || !(suu[b] > 0.0) || std::abs(sxu[b]) == 0.0) continue;
    const Complex h = closed_loop ? sxy[b] / sxu[b] : sxy[b] / sxx[b];
    double coherence = syy[b] > 0.0 ? std::norm(sxy[b]) / (sxx[b] * syy[b]) : 0.0;
    double eps2 = relative_error2(std::min(coherence, 1.0));
    if (closed_loop) {
      const double coherence_ru = std::norm(sxu[b]) / (sxx[b] * suu[b]);
      eps2 += relative_error2(std::min(coherence_ru, 1.0));
      coherence = 1.0 / (1.0 + 2.0 * effective * eps2);
    }
    out.frequency.push_back(static_cast<double>(b) * out.resolution);
    out.response.push_back(h);
    out.coherence.push_back(std::clamp(coherence, 0.0, 1.0));
    out.log_magnitude_std.push_back(std::sqrt(eps2));
    out.phase_std.push_back(std::sqrt(eps2));
    out.excitation.push_back(sxx[b] / averages);
  }
  return out;
}

// The output less its drift: a periodic response plus a constant speed
// (a position read while the joint turns) has a ramp that is the same in
// every period, so it does not average out and leaks into every line as a
// sawtooth's spectrum. Its slope is the least-squares slope of the used
// periods' means (from `first` on: the settling period stays out) against
// their index, divided by the period, which a periodic signal leaves
// untouched; the ramp is removed from every sample.
std::vector<double> WithoutDrift(const std::vector<double>& y, std::size_t period, std::size_t first) {
  const std::size_t whole = y.size() / period;
  if (whole < first + 2) return y;
  const std::size_t used = whole - first;
  std::vector<double> means(used, 0.0);
  for (std::size_t i = 0; i < used; ++i) {
    for (std::size_t k = 0; k < period; ++k) means[i] += y[(first + i) * period + k];
    means[i] /= static_cast<double>(period);
  }
  const double centre = 0.5 * static_cast<double>(used - 1);
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < used; ++i) {
    num += (static_cast<double>(i) - centre) * means[i];
    den += (static_cast<double>(i) - centre) * (static_cast<double>(i) - centre);
  }
  const double slope = num / den / static_cast<double>(period);  // per sample
  std::vector<double> out(y.size());
  for (std::size_t k = 0; k < y.size(); ++k) out[k] = y[k] - slope * static_cast<double>(k);
  return out;
}

FrequencyResponse EstimatePeriodic(const std::vector<FrequencyRecord>& records, double rate, std::size_t period,
                                   bool closed_loop) {
  const std::size_t bins = period / 2 + 1;
  std::vector<std::vector<Complex>> u_spectra, y_spectra;
  std::vector<double> excitation(bins, 0.0);  // |mean spectrum| of the reference (closed loop) or input
  Eigen::FFT<double> fft;
  for (const auto& r : records) {
    // The first period settles when there are enough others.
    const std::size_t whole = r.input.size() / period;
    const std::size_t first = whole >= 3 ? 1 : 0;
    const std::vector<double> output = WithoutDrift(r.output, period, first);
    for (std::size_t begin = first * period; begin + period <= r.input.size(); begin += period) {
      u_spectra.push_back(SegmentSpectrum(fft, r.input, begin, period, {}, false));
      y_spectra.push_back(SegmentSpectrum(fft, output, begin, period, {}, false));
      const auto x = closed_loop ? SegmentSpectrum(fft, r.reference, begin, period, {}, false) : u_spectra.back();
      for (std::size_t b = 0; b < bins; ++b) excitation[b] += std::abs(x[b]);
    }
  }
  const std::size_t m = u_spectra.size();
  if (m < static_cast<std::size_t>(kMinAverages)) {
    throw InputError(fmt::format("the excitation repeats every {} samples, but the logs hold {} whole periods; at least "
                                 "{} are needed (or use ‹method› welch)",
                                 period, m, kMinAverages));
  }
  FrequencyResponse out;
  out.averages = static_cast<int>(m);
  out.resolution = rate / static_cast<double>(period);
  out.closed_loop = closed_loop;
  out.method = FrequencyMethod::kPeriodic;
  out.description = fmt::format("periodic: {} periods of {} samples averaged (rectangular window; a log's first "
                                "period left out to settle when it holds three or more; the output's drift across periods "
                                "removed), noise variance from the spread between periods",
                                m, period);
  double peak = 0.0;
  std::vector<Complex> u_mean(bins, 0.0), y_mean(bins, 0.0);
  for (std::size_t b = 0; b < bins; ++b) {
    for (std::size_t i = 0; i < m; ++i) {
      u_mean[b] += u_spectra[i][b];
      y_mean[b] += y_spectra[i][b];
    }
    u_mean[b] /= static_cast<double>(m);
    y_mean[b] /= static_cast<double>(m);
    if (b > 0) peak = std::max(peak, excitation[b]);
  }
  const double md = static_cast<double>(m);
  for (std::size_t b = 1; b < bins; ++b) {
    // An excited line of the excitation (reference or input).
    if (!(excitation[b] > 1e-3 * peak)) continue;
    double var_u = 0.0, var_y = 0.0, suu = 0.0, syy = 0.0;
    Complex cov_yu = 0.0, suy = 0.0;
    for (std::size_t i = 0; i < m; ++i) {
      const Complex du = u_spectra[i][b] - u_mean[b], dy = y_spectra[i][b] - y_mean[b];
      var_u += std::norm(du);
      var_y += std::norm(dy);
      cov_yu += dy * std::conj(du);
      suu += std::norm(u_spectra[i][b]);
      syy += std::norm(y_spectra[i][b]);
      suy += std::conj(u_spectra[i][b]) * y_spectra[i][b];
    }
    // Variances of the means.
    var_u /= md * (md - 1.0);
    var_y /= md * (md - 1.0);
    cov_yu /= md * (md - 1.0);
    const Complex h = y_mean[b] / u_mean[b];
    // Relative variance of H = Y/U to first order, split evenly between
    // ln|H| and the phase (circular complex noise).
    const double relative = var_y / std::norm(y_mean[b]) + var_u / std::norm(u_mean[b]) -
                            2.0 * std::real(cov_yu / (y_mean[b] * std::conj(u_mean[b])));
    if (!std::isfinite(relative)) continue;
    const double eps = std::sqrt(std::max(relative, 0.0) / 2.0);
    out.frequency.push_back(static_cast<double>(b) * out.resolution);
    out.response.push_back(h);
    out.coherence.push_back(syy > 0.0 ? std::clamp(std::norm(suy) / (suu * syy), 0.0, 1.0) : 0.0);
    out.log_magnitude_std.push_back(eps);
    out.phase_std.push_back(eps);
    out.excitation.push_back(std::pow(excitation[b] / md, 2));
  }
  if (out.frequency.empty()) throw InputError("the periodic excitation excites no frequency line");
  return out;
}

}  // namespace

std::vector<char> ExcitedBins(const std::vector<double>& excitation, std::size_t bins) {
  if (excitation.empty()) return std::vector<char>(bins, 1);
  constexpr std::size_t kHalf = 6;
  double level = 0.0;
  std::vector<double> window, median(excitation.size());
  for (std::size_t b = 0; b < excitation.size(); ++b) {
    window.assign(excitation.begin() + static_cast<std::ptrdiff_t>(b >= kHalf ? b - kHalf : 0),
                  excitation.begin() + static_cast<std::ptrdiff_t>(std::min(b + kHalf + 1, excitation.size())));
    median[b] = Median(window);
    level = std::max(level, median[b]);
  }
  // A bin is excited with its neighbourhood: an isolated line is not a band.
  std::vector<char> excited(excitation.size());
  for (std::size_t b = 0; b < excitation.size(); ++b) {
    excited[b] = excitation[b] >= kExcitedPowerRatio * level && median[b] >= kExcitedPowerRatio * level;
  }
  return excited;
}

std::size_t DetectPeriod(const std::vector<double>& signal) {
  const std::size_t n = signal.size();
  if (n < 16) return 0;
  double mean = 0.0;
  for (double v : signal) mean += v;
  mean /= static_cast<double>(n);
  std::vector<double> x(n, 0.0);
  double energy = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    x[k] = signal[k] - mean;
    energy += x[k] * x[k];
  }
  if (!(energy > 0.0)) return 0;
  // Autocorrelation through the FFT, padded to at least twice the length
  // (lags up to n - 1; those above n / 2 + 1 are not used).
  const std::vector<double> correlation = LaggedProducts(x, n - 1);
  const double r0 = correlation[0];
  int checked = 0;
  for (std::size_t lag = kMinPeriodSamples; lag <= n / 2 && checked < 64; ++lag) {
    const double r = correlation[lag] / r0 * static_cast<double>(n) / static_cast<double>(n - lag);
    if (r < 0.9 || correlation[lag] < correlation[lag - 1] || correlation[lag] < correlation[lag + 1]) continue;
    ++checked;
    bool repeats = true;
    for (std::size_t multiple = 1; multiple <= 2 && repeats; ++multiple) {
      const std::size_t shift = multiple * lag;
      if (multiple == 2 && 3 * lag > n) break;
      double difference = 0.0, power = 0.0;
      for (std::size_t k = 0; k + shift < n; ++k) {
        const double d = signal[k + shift] - signal[k];
        difference += d * d;
        power += x[k] * x[k];
      }
      repeats = difference <= kPeriodTolerance * kPeriodTolerance * power;
    }
    if (repeats) return lag;
  }
  return 0;
}

FrequencyResponse EstimateFrequencyResponse(const std::vector<FrequencyRecord>& records, double rate,
                                            const FrequencyResponseOptions& options) {
  RequireValid(options);
  bool closed_loop = false;
  CheckRecords(records, closed_loop);
  if (!(rate > 0.0) || !std::isfinite(rate)) throw InputError("the sample rate is not a positive number");
  std::size_t longest = 0;
  for (const auto& r : records) longest = std::max(longest, r.input.size());
  if (options.period > 0.0 && !(options.period * rate <= static_cast<double>(longest) / 2.0)) {
    throw OptionError(fmt::format("‹period› {} s: longer than half the longest log ({} samples at {} Hz)",
                                  options.period, longest, rate));
  }
  std::size_t period = options.period > 0.0 ? static_cast<std::size_t>(std::lround(options.period * rate)) : 0;
  if (options.period > 0.0 && std::abs(static_cast<double>(period) - options.period * rate) > 1e-6 * options.period * rate) {
    throw OptionError(fmt::format("‹period› {} s: not a whole number of samples at {} Hz", options.period, rate));
  }
  if (options.period > 0.0 && period < kMinPeriodSamples) {
    // The detector's shortest lag too: fewer samples excite no line between
    // DC and Nyquist.
    throw OptionError(fmt::format("‹period› {} s: {} samples at {} Hz; a period needs at least {}", options.period,
                                  period, rate, kMinPeriodSamples));
  }
  if (options.method == FrequencyMethod::kPeriodic && period == 0) {
    // Every record must repeat with one period.
    const auto& excitation = closed_loop ? records.front().reference : records.front().input;
    period = DetectPeriod(excitation);
    if (period == 0) throw InputError("‹method› periodic: the excitation does not repeat (give ‹period› S)");
  }
  if (options.method == FrequencyMethod::kAuto && period == 0) {
    std::size_t common = 0;
    for (const auto& r : records) {
      const std::size_t p = DetectPeriod(closed_loop ? r.reference : r.input);
      if (p == 0 || (common != 0 && p != common)) {
        common = 0;
        break;
      }
      common = p;
    }
    std::size_t periods = 0;
    for (const auto& r : records) periods += common > 0 ? r.input.size() / common : 0;
    if (common > 0 && periods >= static_cast<std::size_t>(kMinAverages)) period = common;
  }
  if (period > 0 && options.method != FrequencyMethod::kWelch) {
    if (options.resolution > 0.0) {
      throw OptionError(fmt::format("‹resolution› {:g} Hz: the excitation repeats every {:g} s, so the periodic method "
                                    "reads its lines, {:g} Hz apart; give ‹method› welch to choose the resolution",
                                    options.resolution, static_cast<double>(period) / rate,
                                    rate / static_cast<double>(period)));
    }
    return EstimatePeriodic(records, rate, period, closed_loop);
  }
  return EstimateWelch(records, rate, options.resolution, closed_loop);
}

}  // namespace driveid
