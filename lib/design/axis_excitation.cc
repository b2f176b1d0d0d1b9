#include "design/axis_excitation.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <optional>
#include <random>
#include <utility>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/fit_result.h"
#include "core/option_check.h"
#include "core/order_statistics.h"
#include "design/nelder_mead.h"
#include "models/axis_term.h"

namespace driveid {

bool AxisDesignOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& text) {
    *error = text;
    return false;
  };
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(duration)) return fail(ViolatedConstraint("‹duration›", duration, "duration > 0 s"));
  if (!positive(rate)) return fail(ViolatedConstraint("‹rate›", rate, "rate > 0 Hz"));
  if (!(period == 0.0 || (positive(period) && period <= duration))) {
    return fail(ViolatedConstraint("‹period›", period, "0 < period <= duration"));
  }
  if (!positive(max_position)) return fail(ViolatedConstraint("‹max_position›", max_position, "> 0"));
  if (!positive(max_rate)) return fail(ViolatedConstraint("‹max_speed›", max_rate, "> 0"));
  if (!(max_acceleration == 0.0 || positive(max_acceleration))) {
    return fail(ViolatedConstraint("‹max_acceleration›", max_acceleration, "> 0"));
  }
  if (!positive(max_torque)) return fail(ViolatedConstraint("‹max_torque›", max_torque, "> 0"));
  if (!(std::isfinite(band_low) && band_low >= 0.0 && std::isfinite(band_high) && band_high >= 0.0 &&
        (band_high == 0.0 || band_high > band_low))) {
    return fail(fmt::format("‹band› {},{}: violated constraint: 0 <= low < high", band_low, band_high));
  }
  if (!(band_high < rate / 2.0)) {
    return fail(fmt::format("‹band› {},{}: the top line must lie below the Nyquist frequency ‹rate› / 2 = {} Hz", band_low,
                            band_high, rate / 2.0));
  }
  if (lines < 2 || lines > 40) return fail(ViolatedConstraint("‹lines›", lines, "2 <= lines <= 40"));
  if (criterion != "d" && criterion != "a") return fail("‹criterion› " + criterion + ": choose d or a");
  if (!(std::isfinite(noise) && noise >= 0.0)) return fail(ViolatedConstraint("‹noise›", noise, "noise >= 0"));
  if (free.empty()) return fail("‹free›: no parameter to design for");
  return true;
}

namespace {

// Every term present is affine in the rate within a direction of motion
// (models/axis_term.h): the torque over a trajectory scales in closed form.
bool OnlyModeAffine(const AxisParameters& prior) {
  const AxisValues values = AxisValuesOf(prior);
  for (const AxisTerm* term : AxisTerms()) {
    if (!term->mode_affine() && term->Present(&values[AxisFirstIndex(*term)])) return false;
  }
  return true;
}

}  // namespace

namespace {

// One period on a grid, with the prior and the free terms.
struct DesignProblem {
  AxisParameters prior;
  std::vector<int> terms;       // parameter indices (CalcAxisRegressors)
  std::vector<double> scales;   // |prior| (1 where the prior is 0): relative stds
  std::vector<double> grid;     // times over one period
  double period = 0.0;          // [s]
  std::size_t exclusion_reach = 0;  // the fit's, in logged samples
  std::vector<bool> target;     // A: counted
  const AxisDesignOptions* options = nullptr;
  double information_scale = 0.0;  // T f_s / (M sigma^2 0.8) per grid sum, sigma = 1
  std::vector<double> omega;                // the design's lines [rad/s]
  std::vector<std::vector<double>> cosine, sine;  // per line, on the grid
};

struct Kinematics {
  std::vector<double> q, qd, qdd;
};

Kinematics Evaluate(const FourierReference& r, const std::vector<double>& grid) {
  Kinematics k;
  for (double t : grid) {
    const ReferenceSample3 s = r.At(t);
    k.q.push_back(s.position);
    k.qd.push_back(s.rate);
    k.qdd.push_back(s.acceleration);
  }
  return k;
}

// The same for the design's own lines, from the tables (the optimiser's path).
Kinematics EvaluateOnTables(const FourierReference& r, const DesignProblem& p) {
  const std::size_t m = p.grid.size();
  Kinematics k{std::vector<double>(m, 0.0), std::vector<double>(m, 0.0), std::vector<double>(m, 0.0)};
  for (std::size_t line = 0; line < p.omega.size(); ++line) {
    const double a = r.cosine[line], b = r.sine[line], w = p.omega[line];
    const std::vector<double>& c = p.cosine[line];
    const std::vector<double>& n = p.sine[line];
    for (std::size_t i = 0; i < m; ++i) {
      k.q[i] += a * (c[i] - 1.0) + b * n[i];
      k.qd[i] += w * (b * c[i] - a * n[i]);
      k.qdd[i] -= w * w * (a * c[i] + b * n[i]);
    }
  }
  return k;
}

double MaxAbs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

double MaxTorque(const Kinematics& k, double s, const AxisParameters& prior) {
  double m = 0.0;
  for (std::size_t i = 0; i < k.q.size(); ++i) {
    m = std::max(m, std::abs(CalcAxisForce(prior, s * k.q[i], s * k.qd[i], s * k.qdd[i])));
  }
  return m;
}

// The largest s with |tau(s)| <= limit at every sample, for a prior whose
// torque is s d + c with c set by the direction alone (every term present
// mode-affine, OnlyModeAffine): per sample s <= (limit - c sgn d) / |d|; 0
// where |c| > limit.
double LargestTorqueScale(const Kinematics& k, const AxisParameters& p, double limit) {
  double s = HUGE_VAL;
  for (std::size_t i = 0; i < k.q.size(); ++i) {
    const double v = k.qd[i];
    const int dir = (v > 0.0) - (v < 0.0);
    const double d = p.inertia * k.qdd[i] + p.viscous * v + p.viscous_pos * std::max(v, 0.0) +
                     p.viscous_neg * std::min(v, 0.0);
    const double c = p.offset + dir * p.coulomb + (dir > 0 ? p.coulomb_pos : dir < 0 ? -p.coulomb_neg : 0.0);
    if (std::abs(c) > limit) return 0.0;
    if (d > 0.0) s = std::min(s, (limit - c) / d);
    if (d < 0.0) s = std::min(s, (limit + c) / -d);
  }
  return s;
}

// The largest s with every limit kept on the grid, and the limit that binds.
double LargestScale(const Kinematics& k, const DesignProblem& p, std::string* binding) {
  const AxisDesignOptions& o = *p.options;
  double s = HUGE_VAL;
  auto limit = [&](double peak, double bound, const char* name) {
    if (bound > 0.0 && peak > 0.0 && kKinematicMargin * bound / peak < s) {
      s = kKinematicMargin * bound / peak;
      *binding = name;
    }
  };
  limit(MaxAbs(k.q), o.max_position, "position");
  limit(MaxAbs(k.qd), o.max_rate, "speed");
  limit(MaxAbs(k.qdd), o.max_acceleration, "acceleration");
  if (!std::isfinite(s)) return 0.0;
  const double torque = kTorqueMargin * o.max_torque;
  const AxisParameters& prior = p.prior;
  if (OnlyModeAffine(prior)) {
    const double st = LargestTorqueScale(k, prior, torque);
    if (st < s) {
      s = st;
      *binding = "torque";
    }
    return s;
  }
  if (MaxTorque(k, s, prior) <= torque) return s;
  *binding = "torque";
  double lo = 0.0, hi = s;
  for (int i = 0; i < 40; ++i) {
    const double mid = 0.5 * (lo + hi);
    (MaxTorque(k, mid, prior) <= torque ? lo : hi) = mid;
  }
  return lo;
}

// Information of the free terms (sigma = 1) along a scaled reference.
Eigen::MatrixXd Information(const Kinematics& k, double s, const DesignProblem& p) {
  const std::size_t n = p.terms.size();
  std::vector<double> sum(n * n, 0.0), phi(n);
  // The fit leaves out the samples within its filter's reach of a slow one
  // (fit/axis/axis_rows.cc BuildAxisRows): the same on the periodic grid.
  const std::size_t m = k.q.size();
  const double min_rate = 0.01 * s * MaxAbs(k.qd);
  std::vector<char> left_out(m, 0);
  const double reach_time = static_cast<double>(p.exclusion_reach) / p.options->rate;
  const auto reach = static_cast<std::ptrdiff_t>(std::ceil(reach_time * static_cast<double>(m) / p.period));
  for (std::size_t i = 0; i < m; ++i) {
    // Slow on the grid, or a reversal between two grid points (the grid can
    // step over the short slow stretch of a fast reversal).
    const double next = k.qd[(i + 1) % m];
    if (!(std::abs(s * k.qd[i]) < min_rate) && !(k.qd[i] * next < 0.0)) continue;
    for (std::ptrdiff_t j = -reach; j <= reach; ++j) {
      const std::ptrdiff_t at = (static_cast<std::ptrdiff_t>(i) + j) % static_cast<std::ptrdiff_t>(m);
      left_out[static_cast<std::size_t>(at < 0 ? at + static_cast<std::ptrdiff_t>(m) : at)] = 1;
    }
  }
  for (std::size_t i = 0; i < m; ++i) {
    if (left_out[i]) continue;
    const auto all = CalcAxisRegressors(s * k.q[i], s * k.qd[i], s * k.qdd[i]);
    for (std::size_t j = 0; j < n; ++j) phi[j] = all[static_cast<std::size_t>(p.terms[j])];
    for (std::size_t a = 0; a < n; ++a) {
      for (std::size_t b = 0; b <= a; ++b) sum[a * n + b] += phi[a] * phi[b];
    }
  }
  Eigen::MatrixXd info(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = 0; b <= a; ++b) {
      info(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) =
          info(static_cast<Eigen::Index>(b), static_cast<Eigen::Index>(a)) = sum[a * n + b] * p.information_scale;
    }
  }
  return info;
}

// The criterion (smaller is better) of an information matrix.
double Criterion(const Eigen::MatrixXd& info, const DesignProblem& p) {
  const Eigen::VectorXd w = Eigen::Map<const Eigen::VectorXd>(p.scales.data(), static_cast<Eigen::Index>(p.scales.size()));
  const Eigen::MatrixXd scaled = w.asDiagonal() * info * w.asDiagonal();
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(scaled);
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 1e-300)) return HUGE_VAL;
  if (p.options->criterion == "d") return -ldlt.vectorD().array().log().sum();
  const Eigen::MatrixXd cov = ldlt.solve(Eigen::MatrixXd::Identity(scaled.rows(), scaled.cols()));
  double sum = 0.0;
  for (Eigen::Index j = 0; j < cov.rows(); ++j) {
    if (p.target[static_cast<std::size_t>(j)]) sum += cov(j, j);
  }
  return std::log(sum);
}

std::vector<int> Harmonics(int low, int high, int count) {
  std::vector<int> h;
  if (high - low + 1 <= count) {
    for (int n = low; n <= high; ++n) h.push_back(n);
    return h;
  }
  for (int i = 0; i < count; ++i) {
    const int n = static_cast<int>(std::lround(low * std::pow(static_cast<double>(high) / low, i / (count - 1.0))));
    if (h.empty() || n > h.back()) h.push_back(std::max(n, h.empty() ? low : h.back() + 1));
  }
  return h;
}

AxisDesignCandidate Finish(std::string name, const FourierReference& shape, const DesignProblem& p,
                           const std::vector<std::string>& free) {
  const AxisDesignOptions& o = *p.options;
  AxisDesignCandidate c;
  c.name = std::move(name);
  const Kinematics k = Evaluate(shape, p.grid);
  double s = LargestScale(k, p, &c.binding);
  // The limits on the logging grid (the design grid is coarser).
  const double period = 1.0 / shape.base_frequency;
  SampledReference fine = SampleReference(ScaledReference(shape, s), p.prior, o.rate, period);
  for (int pass = 0; pass < 8; ++pass) {
    double excess = std::max({MaxAbs(fine.position) / o.max_position, MaxAbs(fine.rate) / o.max_rate,
                              o.max_acceleration > 0.0 ? MaxAbs(fine.acceleration) / o.max_acceleration : 0.0});
    excess = std::max(excess * kKinematicMargin, MaxAbs(fine.torque) / (kTorqueMargin * o.max_torque));
    if (excess <= 1.0) break;
    s /= excess * 1.0001;
    fine = SampleReference(ScaledReference(shape, s), p.prior, o.rate, period);
  }
  c.reference = ScaledReference(shape, s);
  c.peaks = {MaxAbs(fine.position), MaxAbs(fine.rate), MaxAbs(fine.acceleration), MaxAbs(fine.torque)};
  const Eigen::MatrixXd info = Information(k, s, p) / (o.noise * o.noise);
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(info);
  c.covariance = ldlt.solve(Eigen::MatrixXd::Identity(info.rows(), info.cols()));
  double log_sum = 0.0;
  for (std::size_t j = 0; j < free.size(); ++j) {
    const double sd = std::sqrt(std::max(0.0, c.covariance(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(j))));
    c.predicted_std.push_back(sd);
    log_sum += std::log(sd / p.scales[j]);
  }
  c.geometric_mean_relative_std = std::exp(log_sum / static_cast<double>(free.size()));
  return c;
}

}  // namespace

double NoiseFromIdimResiduals(const std::vector<std::pair<std::string, double>>& rmse,
                              const std::vector<std::pair<std::string, double>>& inflation) {
  std::vector<double> noise;
  const std::string suffix = kTorqueChannelSuffix;
  for (const auto& [channel, value] : rmse) {
    if (channel.size() < suffix.size() || channel.compare(channel.size() - suffix.size(), suffix.size(), suffix) != 0) continue;
    if (!(std::isfinite(value) && value > 0.0)) continue;
    double factor = 1.0;
    for (const auto& [name, f] : inflation) {
      if (name == channel && std::isfinite(f) && f > 1.0) factor = f;
    }
    noise.push_back(value * factor * std::sqrt(kDesignDecimation / kDesignDecimationBand));
  }
  return Median(std::move(noise));
}

SampledReference SampleReference(const FourierReference& reference, const AxisParameters& prior, double rate,
                                 double duration) {
  SampledReference out;
  const long samples = std::lround(duration * rate) + 1;
  for (long i = 0; i < samples; ++i) {
    const double t = static_cast<double>(i) / rate;
    const ReferenceSample3 s = reference.At(t);
    out.time.push_back(t);
    out.position.push_back(s.position);
    out.rate.push_back(s.rate);
    out.acceleration.push_back(s.acceleration);
    out.torque.push_back(CalcAxisForce(prior, s.position, s.rate, s.acceleration));
  }
  return out;
}

namespace {

DesignProblem MakeProblem(const AxisParameters& prior, const AxisDesignOptions& o, double period,
                          const std::vector<int>& harmonics) {
  const int top = harmonics.back();
  DesignProblem p;
  p.prior = prior;
  p.options = &o;
  const auto& table = AxisParameterTable();
  const std::vector<std::string> targets = o.targets.empty() ? o.free : o.targets;
  for (const auto& key : o.free) {
    int index = -1;
    for (std::size_t j = 0; j < AxisLinearCount(); ++j) {
      if (AxisTermRow(j).spec.key == key) index = static_cast<int>(j);
    }
    if (index < 0) {
      throw OptionError(fmt::format("‹free› {}: the design predicts the linear terms only (choose from {})", key,
                                    fmt::join(FitParameterKeys(table, "axis"), ", ")));
    }
    p.terms.push_back(index);
    const double value = std::abs(ModelValue(AxisTermRow(static_cast<std::size_t>(index)), prior));
    p.scales.push_back(value > 0.0 ? value : 1.0);
    p.target.push_back(std::find(targets.begin(), targets.end(), key) != targets.end());
  }
  for (const auto& key : targets) {
    if (std::find(o.free.begin(), o.free.end(), key) == o.free.end()) {
      throw OptionError(fmt::format("‹target› {}: not among the free parameters", key));
    }
  }
  // 40 grid points per period of the highest line, at least 400, at most
  // 16000 (the logging grid checks the limits between).
  const int m = std::min(16000, std::max(400, 40 * top));
  for (int i = 0; i < m; ++i) p.grid.push_back(period * i / m);
  p.period = period;
  const int decimation = static_cast<int>(kDesignDecimation);
  p.exclusion_reach = static_cast<std::size_t>(kDesignExclusionDecimations * decimation);
  for (int n : harmonics) {
    const double w = 2.0 * M_PI * n / period;
    p.omega.push_back(w);
    std::vector<double> c, sn;
    for (double t : p.grid) {
      c.push_back(std::cos(w * t));
      sn.push_back(std::sin(w * t));
    }
    p.cosine.push_back(std::move(c));
    p.sine.push_back(std::move(sn));
  }
  p.information_scale = o.duration * o.rate / (static_cast<double>(m) * kDesignDecimationBand);
  return p;
}

// The highest line the limits make worth exciting: twice the frequency at
// which a sine at the speed limit reaches the acceleration the torque (or
// the acceleration limit) allows, or at which one at the position limit
// reaches the speed limit; below rate / 150, so that the fit's position
// filter (at least 6 x the highest line) stays inside its decimated band.
double DefaultBandHigh(const AxisParameters& prior, const AxisDesignOptions& o) {
  // Each term's bound (models/axis_term.h ForceBound): constant parts add
  // up; the speed parts of terms that replace each other do not.
  const AxisValues values = AxisValuesOf(prior);
  double constant = 0.0, per_rate = 0.0;
  for (const AxisTerm* term : AxisTerms()) {
    double c = 0.0, r = 0.0;
    term->ForceBound(&values[AxisFirstIndex(*term)], &c, &r);
    constant += c;
    per_rate = std::max(per_rate, r);
  }
  const double friction = constant + per_rate * o.max_rate;
  const double spare = kTorqueMargin * o.max_torque - friction;
  if (!(spare > 0.0)) {
    throw OptionError(fmt::format("‹max_torque› {}: the prior's friction at ‹max_speed› {} already needs {:.4g}; "
                                  "lower the speed or raise the torque limit", o.max_torque, o.max_rate, friction));
  }
  double acceleration = prior.inertia > 0.0 ? spare / prior.inertia : HUGE_VAL;
  if (o.max_acceleration > 0.0) acceleration = std::min(acceleration, o.max_acceleration);
  double f = std::max(o.max_rate / (2.0 * M_PI * o.max_position), std::isfinite(acceleration)
                                                                       ? acceleration / (2.0 * M_PI * o.max_rate)
                                                                       : 0.0);
  return std::min(2.0 * f, o.rate / 150.0);
}

std::vector<double> StartShape(const std::vector<int>& h, int kind, std::mt19937_64& rng) {
  const std::size_t lines = h.size();
  std::vector<double> x(2 * (lines - 1));
  std::uniform_real_distribution<double> phase(0.0, 2.0 * M_PI);
  for (std::size_t k = 1; k < lines; ++k) {
    const double ratio = static_cast<double>(h[0]) / h[k];
    const double amplitude = kind == 0 ? 1.0 : kind == 1 ? ratio : ratio * ratio;
    // Schroeder's phases for the first start, random ones after.
    const double ph = kind == 0 ? -M_PI * static_cast<double>(k * (k + 1)) / static_cast<double>(lines) : phase(rng);
    x[k - 1] = amplitude * std::cos(ph);
    x[lines - 1 + k - 1] = amplitude * std::sin(ph);
  }
  return x;
}

// The design with one period; `criterion`: its value (smaller is better).
AxisDesign DesignAtPeriod(const AxisParameters& prior, const AxisDesignOptions& o, double period, double* criterion) {
  AxisDesign d;
  d.free = o.free;
  d.noise = o.noise;
  d.period = period;
  const double f0 = 1.0 / d.period;
  d.band_high = o.band_high > 0.0 ? o.band_high : DefaultBandHigh(prior, o);
  d.band_low = o.band_low > 0.0 ? o.band_low : f0;
  // Harmonic numbers counted in double first: a band far above the period's
  // 2000th harmonic must be refused, not wrapped around an int.
  const double low_harmonic = std::max(1.0, std::ceil(d.band_low / f0 - 1e-9));
  const double high_harmonic = std::floor(d.band_high / f0 + 1e-9);
  if (high_harmonic > 2000.0) {
    throw OptionError(fmt::format("‹period› {:.4g} s: the band's top {:.4g} Hz is its {:.0f}th harmonic; at most the 2000th "
                                  "(shorten the period)", d.period, d.band_high, high_harmonic));
  }
  const int low = static_cast<int>(std::min(low_harmonic, 2001.0));
  const int high = static_cast<int>(high_harmonic);
  if (high - low + 1 < 2) {
    throw OptionError(fmt::format("‹band› {:.4g} to {:.4g} Hz holds fewer than two harmonics of 1 / ‹period› = {:.4g} Hz; "
                                  "widen the band or lengthen the period", d.band_low, d.band_high, f0));
  }
  const std::vector<int> h = Harmonics(low, high, o.lines);
  const DesignProblem p = MakeProblem(prior, o, d.period, h);
  for (int term : p.terms) d.prior.push_back(ModelValue(AxisTermRow(static_cast<std::size_t>(term)), prior));
  auto objective = [&](const std::vector<double>& x) {
    const Kinematics k = EvaluateOnTables(MakeRestingReference(f0, h, x), p);
    std::string binding;
    const double s = LargestScale(k, p, &binding);
    if (!(s > 0.0)) return HUGE_VAL;
    return Criterion(Information(k, s, p), p);
  };
  // At most ~3e8 line-samples per start: long periods with many lines stay fast.
  const int evaluations = std::min(o.evaluations, std::max(300, static_cast<int>(3e8 / (static_cast<double>(p.grid.size()) *
                                                                                     static_cast<double>(h.size())))));
  std::mt19937_64 rng(20261126);
  SimplexResult best{{}, HUGE_VAL, 0};
  for (int kind = 0; kind < 6; ++kind) {
    const std::vector<double> x0 = StartShape(h, std::min(kind, 2), rng);
    std::vector<double> step(x0.size(), 0.5);
    SimplexResult r = MinimiseNelderMead(objective, x0, step, 1e-6, evaluations);
    // A restart from the end point (Nelder-Mead can stall on a kink).
    SimplexResult again = MinimiseNelderMead(objective, r.x, step, 1e-7, evaluations / 2);
    d.evaluations += r.evaluations + again.evaluations;
    if (again.value < best.value) best = again;
  }
  if (!std::isfinite(best.value)) {
    throw OptionError("the limits leave no reference that determines every ‹free› parameter");
  }
  *criterion = best.value;
  d.designed = Finish("designed", MakeRestingReference(f0, h, best.x), p, o.free);
  // The hand-made reference it replaces: four equal sines from 0.2 to 2 Hz.
  std::vector<int> four_lines;
  for (double f : {0.2, 0.2 * std::cbrt(10.0), 0.2 * std::cbrt(100.0), 2.0}) {
    const int n = std::max(1, static_cast<int>(std::lround(f / f0)));
    if (four_lines.empty() || n > four_lines.back()) four_lines.push_back(n);
  }
  FourierReference four{f0, four_lines, {}, {}};
  four.cosine.assign(four.harmonics.size(), 0.0);
  four.sine.assign(four.harmonics.size(), 1.0);
  d.naive = Finish("four sines", four, p, o.free);
  return d;
}

}  // namespace

AxisDesign DesignAxisExcitation(const AxisParameters& prior, const AxisDesignOptions& o) {
  RequireValid(o);
  RequireSampleCount(std::round(o.duration * o.rate) + 1, 100, fmt::format("‹duration› {} at ‹rate› {}", o.duration, o.rate));
  if (!(o.noise > 0.0)) throw OptionError("‹noise›: the torque noise is needed to predict stds (none in the prior's fit)");
  double criterion = HUGE_VAL;
  if (o.period > 0.0) return DesignAtPeriod(prior, o, o.period, &criterion);
  // Without a given period: the duration in 1, 2 and 4 x as many periods
  // as it takes periods of at most 10 s (a shorter period repeats more often
  // and puts its lowest line higher), the one whose design is best.
  const double periods = std::ceil(o.duration / 10.0 - 1e-9);
  // The four sines it is compared with keep the longest period (their
  // lines 0.2 to 2 Hz rounded to its harmonics).
  std::optional<AxisDesign> best;
  std::optional<AxisDesignCandidate> naive;
  double best_criterion = HUGE_VAL;
  std::exception_ptr first_error;
  for (const double factor : {1.0, 2.0, 4.0}) {
    try {
      AxisDesign d = DesignAtPeriod(prior, o, o.duration / (periods * factor), &criterion);
      if (!naive) naive = d.naive;
      if (!best || criterion < best_criterion) {
        best = std::move(d);
        best_criterion = criterion;
      }
    } catch (const OptionError&) {
      if (!first_error) first_error = std::current_exception();
    }
  }
  if (!best) std::rethrow_exception(first_error);
  best->naive = *naive;
  return *best;
}

}  // namespace driveid
