#include "fit/frf/response_features.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "core/order_statistics.h"

namespace driveid {
namespace {

using Complex = std::complex<double>;

double Omega(double hz) { return 2.0 * M_PI * hz; }

// Features only below this fraction of the Nyquist frequency (the sampled
// response folds there, and so do the lines of aliased disturbances).
constexpr double kNyquistMargin = 0.8;
// A line of the excitation's spectrum this many times the median of its
// neighbours is a line, not a broadband excitation.
constexpr double kLineProminence = 10.0;
constexpr std::size_t kLineNeighbours = 6;

// A frequency refined from the bins around a peak or notch: near an
// anti-resonance |H_acc|^2 ~ c ((w^2 - w_a^2)^2 + beta w^2), near a resonance
// 1 / |H_acc|^2 has that form, so a quadratic A x^2 + B x + C in x = w^2
// fitted to it (weighted least squares) gives w^4 = C / A whatever the
// damping; the std by the delta method from the values' relative std
// (empty: from the fit's own scatter when it has degrees of freedom).
struct Refined {
  double hz = 0.0, std_hz = 0.0;
  bool ok = false;
};
Refined Quadratic(const std::vector<double>& hz, const std::vector<double>& value,
                  const std::vector<double>& relative_std) {
  const std::size_t m = hz.size();
  const double scale = std::pow(Omega(hz[m / 2]), 2);
  double top = 0.0;
  for (double v : value) top = std::max(top, v);
  Eigen::MatrixXd x(m, 3);
  Eigen::VectorXd y(m), w(m);
  for (std::size_t i = 0; i < m; ++i) {
    const double xi = std::pow(Omega(hz[i]), 2) / scale;
    x.row(static_cast<Eigen::Index>(i)) << xi * xi, xi, 1.0;
    y[static_cast<Eigen::Index>(i)] = value[i] / top;
    const double s = relative_std.empty() ? 1.0 : std::max(relative_std[i], 1e-12) * value[i] / top;
    w[static_cast<Eigen::Index>(i)] = 1.0 / (s * s);
  }
  const Eigen::Matrix3d normal = x.transpose() * w.asDiagonal() * x;
  const Eigen::Vector3d c = normal.ldlt().solve(x.transpose() * w.asDiagonal() * y);
  Refined out;
  out.hz = hz[m / 2];
  const double ratio = c[2] / c[0];
  if (!(c[0] > 0.0) || !(ratio > 0.0) || !std::isfinite(ratio)) return out;
  const double refined = std::sqrt(std::sqrt(ratio) * scale) / (2.0 * M_PI);
  if (!(refined >= hz.front() && refined <= hz.back())) return out;
  out.hz = refined;
  out.ok = true;
  Eigen::Matrix3d cov = normal.inverse();
  if (relative_std.empty()) {
    if (m <= 3) return out;
    const Eigen::VectorXd r = y - x * c;
    cov *= r.dot(w.asDiagonal() * r) / static_cast<double>(m - 3);
  }
  const double var_log = (cov(2, 2) / (c[2] * c[2]) + cov(0, 0) / (c[0] * c[0]) - 2.0 * cov(0, 2) / (c[0] * c[2])) / 16.0;
  out.std_hz = refined * std::sqrt(std::max(var_log, 0.0));
  return out;
}

// Whether bin b of the excitation stands as a line above its neighbours.
bool ExcitationLine(const ResponseData& data, std::size_t b) {
  if (data.excitation.empty()) return false;
  std::vector<double> around;
  const std::size_t first = b >= kLineNeighbours ? b - kLineNeighbours : 0;
  for (std::size_t j = first; j <= std::min(b + kLineNeighbours, data.excitation.size() - 1); ++j) {
    if (j + 1 < b || j > b + 1) around.push_back(data.excitation[j]);
  }
  if (around.size() < 4) return false;
  return data.excitation[b] > kLineProminence * Median(around);
}

// The harmonic of the rotation frequency a bin lies on (within a bin), or 0.
int RotationHarmonic(const ResponseData& data, double hz, double resolution) {
  const double f = data.rotation_hz;
  if (!(f >= 2.0 * resolution)) return 0;
  const int k = static_cast<int>(std::lround(hz / f));
  return k >= 1 && std::abs(hz - k * f) <= resolution ? k : 0;
}

// A resonance turns the phase down across its peak: by 90 degrees between
// its half-power points, by 120 between the points 6 dB down, whatever its
// damping. kMinPhaseTurn is asked between the bins where the level has
// fallen by kTurnDrop on either side (or the window's ends: the band's
// edge, a factor kTurnSpan in frequency, or where the level rises again
// past a notch).
// A maximum of |H| whose phase does not turn (a band edge, a filter's
// corner, noise) is not a mode.
constexpr double kMinPhaseTurn = M_PI / 2.0;
constexpr double kTurnDrop = 0.6931471805599453;  // ln 2: 6 dB
constexpr double kTurnSpan = 1.5;
constexpr double kTurnRise = 0.3453877639491069;  // ln sqrt(2): 3 dB

// The phase's fall [rad] across bins[peak], unwrapped bin to bin.
double PhaseTurn(const ResponseData& motor, const std::vector<std::size_t>& bins, const std::vector<double>& level,
                 std::size_t peak) {
  const std::size_t m = bins.size();
  const double f = motor.frequency[bins[peak]];
  // Outwards from the peak until the level has fallen by kTurnDrop, the
  // span ends, or the level rises kTurnRise above its lowest so far (past a
  // neighbouring anti-resonance, which turns the phase back up).
  const auto walk = [&](std::size_t from, int step) {
    std::size_t at = from;
    double lowest = level[from];
    while (true) {
      const std::size_t next = step < 0 ? at - 1 : at + 1;
      if ((step < 0 && at == 0) || (step > 0 && next >= m)) break;
      const double fn = motor.frequency[bins[next]];
      if (fn < f / kTurnSpan || fn > f * kTurnSpan || level[next] > lowest + kTurnRise) break;
      at = next;
      lowest = std::min(lowest, level[at]);
      if (level[peak] - level[at] >= kTurnDrop) break;
    }
    return at;
  };
  const std::size_t left = walk(peak, -1), right = walk(peak, 1);
  double phase = 0.0;  // unwrapped from `left`
  for (std::size_t j = left + 1; j <= right; ++j) {
    phase += std::arg(motor.response[bins[j]] / motor.response[bins[j - 1]]);
  }
  return -phase;
}

// The largest maximum of the level (ln |H_acc|) at least two bins inside the
// band and a bin below `top` that is a mode: not on a line of the
// excitation, not on a harmonic of the rotation, its phase turning down
// (PhaseTurn). 0: none. What was skipped is said in `notes`.
std::size_t FindPeak(const ResponseData& motor, const std::vector<std::size_t>& bins, const std::vector<double>& level,
                     double top, double resolution, std::vector<std::string>& notes) {
  const std::size_t m = bins.size();
  std::size_t peak = 0, unturned = 0;
  std::string unturned_note;
  for (std::size_t i = 2; i + 2 < m; ++i) {
    if (!(level[i] > level[i - 1] && level[i] >= level[i + 1])) continue;
    if (peak != 0 && level[i] <= level[peak]) continue;
    const double f = motor.frequency[bins[i]];
    if (f + resolution >= top) continue;  // at least a bin below 0.8 x Nyquist
    if (ExcitationLine(motor, bins[i])) {
      notes.push_back(fmt::format("a peak at {:.4g} Hz stands on a line of the excitation's own spectrum: a "
                                      "disturbance passed to the input, not a mode (skipped)",
                                      f));
      continue;
    }
    if (const int k = RotationHarmonic(motor, f, resolution); k > 0) {
      notes.push_back(fmt::format("a peak at {:.4g} Hz lies on harmonic {} of the rotation frequency {:.4g} Hz: a "
                                      "disturbance, not a mode (skipped)",
                                      f, k, motor.rotation_hz));
      continue;
    }
    if (const double turn = PhaseTurn(motor, bins, level, i); !(turn >= kMinPhaseTurn)) {
      if (unturned != 0 && level[unturned] >= level[i]) continue;
      unturned = i;
      unturned_note = (fmt::format("a maximum of |H| at {:.4g} Hz, but the phase changes by {:+.0f} degrees across "
                                      "it (a resonance turns it down by 90 or more): not a mode (skipped)",
                                      f, -turn * 180.0 / M_PI));
      continue;
    }
    peak = i;
  }
  // The highest maximum that was no mode, when it stands above the mode read.
  if (unturned != 0 && (peak == 0 || level[unturned] > level[peak])) notes.push_back(unturned_note);
  return peak;
}

}  // namespace

std::vector<char> BandBins(const ResponseData& data, const ResponseBand& band) {
  double low = band.low, high = band.high;
  const bool given = high > 0.0;
  const std::vector<char> excited_bins = ExcitedBins(data.excitation, data.frequency.size());
  const auto excited = [&](std::size_t b) { return given || excited_bins[b] != 0; };
  if (!given) {
    low = high = 0.0;
    for (std::size_t b = 0; b < data.frequency.size(); ++b) {
      if (!excited(b) || (!data.coherence.empty() && data.coherence[b] < band.min_coherence)) continue;
      if (low == 0.0) low = data.frequency[b];
      high = data.frequency[b];
    }
  }
  std::vector<char> used(data.frequency.size(), 0);
  for (std::size_t b = 0; b < used.size(); ++b) {
    const double f = data.frequency[b];
    const bool in_band = f > 0.0 && f >= low && f <= high && excited(b);
    const bool coherent = data.coherence.empty() || data.coherence[b] >= std::min(0.2, band.min_coherence);
    const bool finite_std = (data.log_magnitude_std.empty() || (std::isfinite(data.log_magnitude_std[b]) &&
                                                                data.log_magnitude_std[b] > 0.0)) &&
                            (data.phase_std.empty() || (std::isfinite(data.phase_std[b]) && data.phase_std[b] > 0.0));
    used[b] = in_band && coherent && finite_std && std::abs(data.response[b]) > 0.0 &&
              std::isfinite(std::abs(data.response[b]));
  }
  return used;
}

void UsedBand(const ResponseData& data, const std::vector<char>& used, double& low, double& high) {
  low = high = 0.0;
  for (std::size_t b = 0; b < used.size(); ++b) {
    if (!used[b]) continue;
    if (low == 0.0) low = data.frequency[b];
    high = data.frequency[b];
  }
}

ResponseFeatures ReadResponseFeatures(const ResponseData& motor, ResponseQuantity quantity, const ResponseBand& band) {
  const std::vector<char> used = BandBins(motor, band);
  ResponseFeatures out;
  UsedBand(motor, used, out.band_low, out.band_high);
  std::vector<std::size_t> bins;
  for (std::size_t b = 0; b < used.size(); ++b) {
    if (used[b]) bins.push_back(b);
  }
  const std::size_t m = bins.size();
  out.bins = m;
  const std::string band_text = fmt::format("{:.4g} .. {:.4g} Hz", out.band_low, out.band_high);
  if (m < kMinResponseBins) {
    out.warnings.push_back(fmt::format("{} usable bins in the excited, coherent band {}: no resonance can be read", m,
                                       band_text));
    return out;
  }
  std::vector<double> level(m);
  for (std::size_t i = 0; i < m; ++i) {
    const double w = Omega(motor.frequency[bins[i]]);
    level[i] = std::log(std::abs(motor.response[bins[i]] * std::pow(Complex(0.0, w), 2 - static_cast<int>(quantity))));
  }
  const double resolution = (motor.frequency[bins.back()] - motor.frequency[bins.front()]) / static_cast<double>(m - 1);
  // Refined from three and from five neighbouring bins, each with the other
  // feature's factor |w^2 - w_other^2|^2 divided out.
  const auto refine = [&](std::size_t i, bool notch, double other_hz) {
    const auto fit = [&](std::size_t half) {
      std::vector<double> hz, value, relative;
      for (std::size_t j = i >= half ? i - half : 0; j <= std::min(i + half, m - 1); ++j) {
        const double f = motor.frequency[bins[j]];
        const double other = std::pow(Omega(f) * Omega(f) - Omega(other_hz) * Omega(other_hz), 2);
        hz.push_back(f);
        value.push_back(notch ? std::exp(2.0 * level[j]) * other : std::exp(-2.0 * level[j]) * other);
        if (!motor.log_magnitude_std.empty()) relative.push_back(2.0 * motor.log_magnitude_std[bins[j]]);
      }
      return Quadratic(hz, value, relative);
    };
    const Refined five = fit(2), three = fit(1);
    FrequencyEstimate e;
    const double width = 0.5 * (motor.frequency[bins[i + 1]] - motor.frequency[bins[i - 1]]);
    if (!five.ok) {
      e.value = motor.frequency[bins[i]];
      e.standard_error = width / std::sqrt(3.0);  // anywhere within the bin, at least
      return e;
    }
    e.value = five.hz;
    const double model = three.ok ? three.hz - five.hz : width / std::sqrt(12.0);
    e.standard_error = std::sqrt(five.std_hz * five.std_hz + model * model);
    if (!(five.std_hz > 0.0)) e.standard_error = std::max(e.standard_error, width / std::sqrt(12.0));
    return e;
  };
  const double top = motor.nyquist_hz > 0.0 ? kNyquistMargin * motor.nyquist_hz : HUGE_VAL;
  const std::size_t peak = FindPeak(motor, bins, level, top, resolution, out.notes);
  if (peak == 0) {
    out.warnings.push_back(fmt::format("no resonance peak inside the excited, coherent band {} (features are read at "
                                       "least two bins inside it{}): excite across the resonance",
                                       band_text, std::isfinite(top) ? fmt::format(" and below {:.4g} Hz", top) : ""));
    return out;
  }
  std::size_t notch = 0;
  for (std::size_t i = 1; i < peak; ++i) {
    if (level[i] < level[i - 1] && level[i] <= level[i + 1] && (notch == 0 || level[i] < level[notch])) notch = i;
  }
  if (notch == 0) {
    out.resonance = refine(peak, false, 0.0);
    return out;
  }
  out.antiresonance = refine(notch, true, motor.frequency[bins[peak]]);
  out.resonance = refine(peak, false, out.antiresonance.value);
  out.antiresonance = refine(notch, true, out.resonance.value);
  return out;
}

}  // namespace driveid
