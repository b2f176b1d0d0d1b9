#include "signal/clock_alignment.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

#include <fmt/format.h>
#include <unsupported/Eigen/FFT>

#include "core/errors.h"
#include "signal/resample.h"

namespace driveid {
namespace {

constexpr std::size_t kMinSamples = 16;

void CheckRecord(const std::vector<double>& t, const std::vector<double>& x, const char* name) {
  if (t.size() != x.size() || t.size() < kMinSamples) {
    throw std::invalid_argument(fmt::format("clock alignment: record {} needs {} samples and one value each", name,
                                            kMinSamples));
  }
  for (std::size_t k = 1; k < t.size(); ++k) {
    if (!(t[k] > t[k - 1])) throw std::invalid_argument("clock alignment: times must increase strictly");
  }
}

// Mean-removed samples on the grid t0 + k * step.
std::vector<double> OnGrid(const std::vector<double>& t, const std::vector<double>& x, double step) {
  const double span = t.back() - t.front();
  const auto n = static_cast<std::size_t>(std::floor(span / step + 1e-9)) + 1;
  std::vector<double> g = ResampleLinear(t, x, 1.0 / step, n);
  double mean = 0.0;
  for (double v : g) mean += v;
  mean /= static_cast<double>(g.size());
  for (double& v : g) v -= mean;
  return g;
}

// c[l] = sum_j a[j + l] b[j] for every lag l in -(nb - 1) .. na - 1, at index l + nb - 1.
std::vector<double> CrossProducts(const std::vector<double>& a, const std::vector<double>& b) {
  std::size_t padded = 2;  // kissfft's one-point plan indexes an empty buffer
  while (padded < a.size() + b.size()) padded *= 2;
  std::vector<double> pa(a), pb(b);
  pa.resize(padded, 0.0);
  pb.resize(padded, 0.0);
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> fa, fb;
  fft.fwd(fa, pa);
  fft.fwd(fb, pb);
  for (std::size_t k = 0; k < padded; ++k) fa[k] *= std::conj(fb[k]);
  std::vector<double> c;
  fft.inv(c, fa);
  const std::size_t nb = b.size();
  std::vector<double> out(a.size() + nb - 1);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const auto lag = static_cast<std::ptrdiff_t>(i) - static_cast<std::ptrdiff_t>(nb - 1);
    out[i] = c[lag >= 0 ? static_cast<std::size_t>(lag) : padded - static_cast<std::size_t>(-lag)];
  }
  return out;
}

// Running sums of x and of x^2 (s[k]: over the first k samples).
struct RunningSums {
  std::vector<double> sum, squares;
  explicit RunningSums(const std::vector<double>& x) : sum(x.size() + 1, 0.0), squares(x.size() + 1, 0.0) {
    for (std::size_t k = 0; k < x.size(); ++k) {
      sum[k + 1] = sum[k] + x[k];
      squares[k + 1] = squares[k] + x[k] * x[k];
    }
  }
};

struct Correlogram {
  std::vector<double> r;  // NaN where the overlap is too short or outside the window
  std::ptrdiff_t first_lag = 0;
};

// Pearson's correlation of the overlapping parts at each lag in lo .. hi
// (each part's own mean removed, so that a drifting mean does not pull the peak).
Correlogram Normalised(const std::vector<double>& a, const std::vector<double>& b, std::ptrdiff_t lo,
                       std::ptrdiff_t hi) {
  const std::vector<double> c = CrossProducts(a, b);
  const RunningSums sa(a), sb(b);
  const auto na = static_cast<std::ptrdiff_t>(a.size()), nb = static_cast<std::ptrdiff_t>(b.size());
  const std::ptrdiff_t min_overlap =
      std::max<std::ptrdiff_t>(static_cast<std::ptrdiff_t>(kMinSamples), (std::min(na, nb) + 1) / 2);
  Correlogram out;
  out.first_lag = -(nb - 1);
  out.r.assign(c.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::ptrdiff_t lag = std::max(lo, -(nb - 1)); lag <= std::min(hi, na - 1); ++lag) {
    const std::ptrdiff_t j0 = std::max<std::ptrdiff_t>(0, -lag), j1 = std::min(nb, na - lag);
    if (j1 - j0 < min_overlap) continue;
    const auto ia0 = static_cast<std::size_t>(j0 + lag), ia1 = static_cast<std::size_t>(j1 + lag);
    const auto ib0 = static_cast<std::size_t>(j0), ib1 = static_cast<std::size_t>(j1);
    const double n = static_cast<double>(j1 - j0);
    const double suma = sa.sum[ia1] - sa.sum[ia0], sumb = sb.sum[ib1] - sb.sum[ib0];
    const double va = sa.squares[ia1] - sa.squares[ia0] - suma * suma / n;
    const double vb = sb.squares[ib1] - sb.squares[ib0] - sumb * sumb / n;
    if (!(va > 0.0 && vb > 0.0)) continue;
    const auto i = static_cast<std::size_t>(lag - out.first_lag);
    out.r[i] = (c[i] - suma * sumb / n) / std::sqrt(va * vb);
  }
  return out;
}

// Pearson's correlation of a's samples with b interpolated at a's times
// minus `shift` (where b has data): no grid, so no grid bias.
double CorrelationAt(const std::vector<double>& ta, const std::vector<double>& xa, const std::vector<double>& tb,
                     const std::vector<double>& xb, double shift) {
  double n = 0.0, sa = 0.0, sb = 0.0, saa = 0.0, sbb = 0.0, sab = 0.0;
  std::size_t j = 0;
  for (std::size_t i = 0; i < ta.size(); ++i) {
    const double t = ta[i] - shift;
    if (t < tb.front() || t > tb.back()) continue;
    while (j + 2 < tb.size() && tb[j + 1] < t) ++j;
    const double w = std::clamp((t - tb[j]) / (tb[j + 1] - tb[j]), 0.0, 1.0);
    const double b = xb[j] + w * (xb[j + 1] - xb[j]), a = xa[i];
    n += 1.0;
    sa += a;
    sb += b;
    saa += a * a;
    sbb += b * b;
    sab += a * b;
  }
  const double va = saa - sa * sa / n, vb = sbb - sb * sb / n;
  return n > 2.0 && va > 0.0 && vb > 0.0 ? (sab - sa * sb / n) / std::sqrt(va * vb) : -1.0;
}

// The grid's peak refined on a's own samples: 21 shifts a tenth of a grid
// step apart around it, then a parabola through the best and its neighbours.
void Refine(const std::vector<double>& ta, const std::vector<double>& xa, const std::vector<double>& tb,
            const std::vector<double>& xb, ChannelShift& s) {
  constexpr int kHalf = 10;
  const double h = s.step / kHalf;
  std::vector<double> r(2 * kHalf + 1);
  for (int k = -kHalf; k <= kHalf; ++k) r[static_cast<std::size_t>(k + kHalf)] = CorrelationAt(ta, xa, tb, xb, s.shift + k * h);
  const auto best = static_cast<std::size_t>(std::max_element(r.begin(), r.end()) - r.begin());
  double fraction = 0.0;
  if (best > 0 && best + 1 < r.size()) {
    const double curvature = r[best - 1] - 2.0 * r[best] + r[best + 1];
    if (curvature < 0.0) fraction = std::clamp(0.5 * (r[best - 1] - r[best + 1]) / curvature, -0.5, 0.5);
  }
  s.shift += (static_cast<double>(best) - kHalf + fraction) * h;
  s.correlation = std::max(s.correlation, r[best]);
}

ChannelShift ShiftInWindow(const std::vector<double>& ta, const std::vector<double>& xa,
                           const std::vector<double>& tb, const std::vector<double>& xb, double center,
                           double half_width) {
  CheckRecord(ta, xa, "a");
  CheckRecord(tb, xb, "b");
  ChannelShift out;
  out.step = std::max(MedianStep(ta), MedianStep(tb));
  const std::vector<double> a = OnGrid(ta, xa, out.step), b = OnGrid(tb, xb, out.step);
  // shift = ta0 - tb0 + lag * step.
  const double base = ta.front() - tb.front();
  const auto lag_of = [&](double shift) { return (shift - base) / out.step; };
  const auto lo = static_cast<std::ptrdiff_t>(std::floor(std::max(-1e15, lag_of(center - half_width))));
  const auto hi = static_cast<std::ptrdiff_t>(std::ceil(std::min(1e15, lag_of(center + half_width))));
  const Correlogram g = Normalised(a, b, lo, hi);
  const std::vector<double>& r = g.r;
  std::size_t best = r.size();
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (std::isfinite(r[i]) && (best == r.size() || r[i] > r[best])) best = i;
  }
  if (best == r.size()) return out;  // correlation 0: nothing overlaps enough
  double fraction = 0.0;
  if (best > 0 && best + 1 < r.size() && std::isfinite(r[best - 1]) && std::isfinite(r[best + 1])) {
    const double curvature = r[best - 1] - 2.0 * r[best] + r[best + 1];
    if (curvature < 0.0) fraction = std::clamp(0.5 * (r[best - 1] - r[best + 1]) / curvature, -0.5, 0.5);
  }
  out.correlation = r[best];
  out.shift = base + (static_cast<double>(g.first_lag + static_cast<std::ptrdiff_t>(best)) + fraction) * out.step;
  Refine(ta, xa, tb, xb, out);
  // The main lobe: out from the peak while the correlation stays above half
  // the peak's (noise makes small bumps there) or falls.
  const auto in_lobe = [&](std::size_t next, std::size_t here) {
    return std::isfinite(r[next]) && (r[next] >= 0.5 * r[best] || r[next] <= r[here]);
  };
  std::size_t left = best, right = best;
  while (left > 0 && in_lobe(left - 1, left)) --left;
  while (right + 1 < r.size() && in_lobe(right + 1, right)) ++right;
  for (std::size_t i = 0; i < r.size(); ++i) {
    if ((i >= left && i <= right) || !std::isfinite(r[i]) || r[i] <= out.runner_up_correlation) continue;
    out.runner_up_correlation = r[i];
    out.runner_up_shift = base + static_cast<double>(g.first_lag + static_cast<std::ptrdiff_t>(i)) * out.step;
  }
  return out;
}

void CheckPeak(const ChannelShift& s, const std::string& what) {
  if (!(s.correlation >= kMinAlignmentCorrelation)) {
    throw IdentificationError(fmt::format(
        "{}: the channels do not line up: their best normalised correlation is {:.2f} (at a shift of {:.6g} s), "
        "below {}; align by a channel both logs record, or give the shift",
        what, s.correlation, s.shift, kMinAlignmentCorrelation));
  }
  if (s.runner_up_correlation > s.correlation - kMinAlignmentMargin) {
    throw IdentificationError(fmt::format(
        "{}: the alignment is ambiguous: shifts of {:.6g} s and {:.6g} s correlate alike ({:.3f} and {:.3f}; a "
        "periodic channel?): crop both logs to a stretch that does not repeat, or give the shift",
        what, s.shift, s.runner_up_shift, s.correlation, s.runner_up_correlation));
  }
}

std::vector<double> Slice(const std::vector<double>& v, std::size_t begin, std::size_t end) {
  return {v.begin() + static_cast<std::ptrdiff_t>(begin), v.begin() + static_cast<std::ptrdiff_t>(end)};
}

}  // namespace

ChannelShift ShiftByCrossCorrelation(const std::vector<double>& ta, const std::vector<double>& xa,
                                     const std::vector<double>& tb, const std::vector<double>& xb) {
  return ShiftInWindow(ta, xa, tb, xb, 0.0, std::numeric_limits<double>::infinity());
}

ClockMap AlignClocks(const std::vector<double>& ta, const std::vector<double>& xa, const std::vector<double>& tb,
                     const std::vector<double>& xb, const std::string& what) {
  CheckRecord(ta, xa, "a");
  CheckRecord(tb, xb, "b");
  // The common grid holds span / step samples: gaps would make it huge.
  const double step = std::max(MedianStep(ta), MedianStep(tb));
  for (const auto* t : {&ta, &tb}) {
    if (!((t->back() - t->front()) / step <= 4.0 * static_cast<double>(t->size()) + 1000.0)) {
      throw InputError(fmt::format("{}: a record spans {:.6g} s, {:.3g} times its {} samples at the step {:.6g} s: its "
                                   "time stamps have gaps too long to align across; crop to a stretch without them",
                                   what, t->back() - t->front(), (t->back() - t->front()) / step / static_cast<double>(t->size()),
                                   t->size(), step));
    }
  }
  const ChannelShift whole = ShiftByCrossCorrelation(ta, xa, tb, xb);
  CheckPeak(whole, what);
  ClockMap map;
  map.offset = whole.shift;
  map.correlation = whole.correlation;
  map.notes.push_back(fmt::format("aligned by cross-correlation: shift {:.6g} s (correlation {:.3f}; next peak {:.3f})",
                                  whole.shift, whole.correlation, whole.runner_up_correlation));
  // The thirds, searched near the whole records' shift (a rate difference
  // of 1 % at most): a rate difference when the first and last differ by a
  // tenth of a grid step and four times the middle's distance from their line.
  const std::size_t third = ta.size() / 3;
  if (third < 4 * kMinSamples) return map;
  const double window = 0.01 * (ta.back() - ta.front()) + 4.0 * whole.step;
  ChannelShift part[3];
  double center[3];
  for (std::size_t p = 0; p < 3; ++p) {
    const std::size_t begin = p * third, end = p == 2 ? ta.size() : begin + third;
    part[p] = ShiftInWindow(Slice(ta, begin, end), Slice(xa, begin, end), tb, xb, whole.shift, window);
    center[p] = 0.5 * (ta[begin] + ta[end - 1]);
    if (!(part[p].correlation >= kMinAlignmentCorrelation)) return map;
  }
  const double change = part[2].shift - part[0].shift;
  const double middle_off = part[1].shift - (part[0].shift + change * (center[1] - center[0]) / (center[2] - center[0]));
  if (!(std::abs(change) > 0.1 * whole.step && std::abs(change) > 4.0 * std::abs(middle_off))) return map;
  // a-time c1 <-> b-time c1 - s1, c3 <-> c3 - s3.
  const double c1 = center[0], c3 = center[2];
  map.scale = (c3 - c1) / ((c3 - part[2].shift) - (c1 - part[0].shift));
  map.offset = c1 - map.scale * (c1 - part[0].shift);
  map.notes.push_back(fmt::format(
      "the clocks run at different rates: shift {:.6g} s over the first third, {:.6g} s over the last ({:+.1f} ppm), "
      "corrected linearly",
      part[0].shift, part[2].shift, 1e6 * (map.scale - 1.0)));
  return map;
}

}  // namespace driveid
