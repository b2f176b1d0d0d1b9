#include "fit/frf/frequency_response_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"
#include "core/order_statistics.h"
#include "fit/core/adequacy.h"
#include "models/missing_values.h"

namespace driveid {

bool TwoMassFitOptions::IsValid(std::string* error) const {
  return OptionCheck(error)
      .Require(NotNegative(band_low), "‹band› low", band_low, ">= 0 Hz")
      .Require(NotNegative(band_high) && (band_high == 0.0 || band_high > band_low), "‹band› high", band_high,
               "above the low end (0, 0: the coherent bins)")
      .Require(min_coherence >= 0.0 && min_coherence <= 1.0, "min_coherence", min_coherence, "0 <= coherence <= 1")
      .Require(NotNegative(hold_rate), "hold_rate", hold_rate, "rate >= 0 Hz (0: continuous)")
      .Nested(fit);
}
namespace {

using Complex = std::complex<double>;

// The dynamic terms in the order of JointResponse's gradients, then the delay.
constexpr std::size_t kDelay = 6;
const std::array<double JointParameters::*, 6> kMembers = {
    &JointParameters::motor_inertia, &JointParameters::link_inertia,  &JointParameters::stiffness,
    &JointParameters::damping,       &JointParameters::motor_viscous, &JointParameters::link_viscous};
// Their keys (models/joint.h's table), then "delay".
const std::array<std::string, 7>& Terms() {
  static const std::array<std::string, 7> terms = [] {
    std::array<std::string, 7> t;
    for (std::size_t i = 0; i < kMembers.size(); ++i) t[i] = KeyOf(JointParameterTable(), kMembers[i]);
    t[kDelay] = "delay";
    return t;
  }();
  return terms;
}

double Omega(double hz) { return 2.0 * M_PI * hz; }


class ResponseResiduals final : public ResidualModel {
 public:
  struct Row {
    const ResponseData* data;
    std::size_t bin;
    bool link, phase;
  };
  ResponseResiduals(std::vector<Row> rows, const JointParameters& fixed, double gear_ratio,
                    std::vector<std::size_t> free_terms, const TwoMassFitOptions& options)
      : rows_(std::move(rows)), fixed_(fixed), gear_ratio_(gear_ratio),
        free_(std::move(free_terms)), options_(options) {}
  int residual_count() const override { return static_cast<int>(rows_.size()); }
  bool Evaluate(const double* parameters, double* residuals, double* jacobian) override {
    JointParameters p = fixed_;
    double delay = 0.0;
    for (std::size_t j = 0; j < free_.size(); ++j) {
      if (free_[j] == kDelay) {
        delay = parameters[j];
      } else {
        p.*(kMembers[free_[j]]) = parameters[j];
      }
    }
    const std::size_t np = free_.size();
    std::vector<Complex> model, gradient;
    if (!Responses(p, delay, jacobian != nullptr, model, gradient)) return false;
    for (std::size_t r = 0; r < rows_.size(); ++r) {
      const Row& row = rows_[r];
      const ResponseData& d = *row.data;
      const Complex log_ratio = std::log(model[r] / d.response[row.bin]);
      const double sigma = row.phase ? (d.phase_std.empty() ? 1.0 : d.phase_std[row.bin])
                                     : (d.log_magnitude_std.empty() ? 1.0 : d.log_magnitude_std[row.bin]);
      residuals[r] = (row.phase ? log_ratio.imag() : log_ratio.real()) / sigma;
      if (jacobian == nullptr) continue;
      for (std::size_t j = 0; j < np; ++j) {
        const Complex dj = gradient[r * np + j];
        jacobian[r * np + j] = (row.phase ? dj.imag() : dj.real()) / sigma;
      }
    }
    return true;
  }

  /// The model at every row and, if asked, d ln(model) / d parameter (row-major).
  bool Responses(const JointParameters& p, double delay, bool with_gradient, std::vector<Complex>& model,
                 std::vector<Complex>& gradient) const {
    const std::size_t np = free_.size();
    model = Values(p, delay);
    for (const Complex& m : model) {
      if (!std::isfinite(std::abs(m)) || std::abs(m) == 0.0) return false;
    }
    if (!with_gradient) return true;
    gradient.assign(rows_.size() * np, 0.0);
    for (std::size_t j = 0; j < np; ++j) {
      if (free_[j] == kDelay) {
        for (std::size_t r = 0; r < rows_.size(); ++r) {
          gradient[r * np + j] = Complex(0.0, -Omega(rows_[r].data->frequency[rows_[r].bin]));
        }
        continue;
      }
      if (options_.hold_rate <= 0.0) {
        for (std::size_t r = 0; r < rows_.size(); ++r) {
          const Row& row = rows_[r];
          const JointResponse g = CalcJointResponse(p, gear_ratio_, Omega(row.data->frequency[row.bin]),
                                                    row.link ? options_.link_output : options_.motor_output);
          gradient[r * np + j] = (row.link ? g.link_log_gradient : g.motor_log_gradient)[free_[j]];
        }
        continue;
      }
      // The sampled response: central differences of ln(model).
      const double value = p.*(kMembers[free_[j]]);
      const double h = 1e-6 * std::max(std::abs(value), 1e-12);
      JointParameters up = p, down = p;
      up.*(kMembers[free_[j]]) = value + h;
      down.*(kMembers[free_[j]]) = std::max(value - h, 0.0);
      const double step = up.*(kMembers[free_[j]]) - down.*(kMembers[free_[j]]);
      const std::vector<Complex> plus = Values(up, delay), minus = Values(down, delay);
      for (std::size_t r = 0; r < rows_.size(); ++r) gradient[r * np + j] = std::log(plus[r] / minus[r]) / step;
    }
    return true;
  }

  std::vector<Complex> Values(const JointParameters& p, double delay) const {
    std::vector<Complex> values(rows_.size());
    if (options_.hold_rate > 0.0) {
      const SampledJointResponse sampled(p, gear_ratio_, options_.hold_rate);
      for (std::size_t r = 0; r < rows_.size(); ++r) {
        const Row& row = rows_[r];
        const double omega = Omega(row.data->frequency[row.bin]);
        values[r] = (row.link ? sampled.Link(omega, options_.link_output) : sampled.Motor(omega, options_.motor_output)) *
                    std::exp(Complex(0.0, -omega * delay));
      }
      return values;
    }
    for (std::size_t r = 0; r < rows_.size(); ++r) {
      const Row& row = rows_[r];
      const double omega = Omega(row.data->frequency[row.bin]);
      const JointResponse g = CalcJointResponse(p, gear_ratio_, omega, row.link ? options_.link_output : options_.motor_output);
      values[r] = (row.link ? g.link : g.motor) * std::exp(Complex(0.0, -omega * delay));
    }
    return values;
  }

 private:
  std::vector<Row> rows_;
  JointParameters fixed_;
  double gear_ratio_;
  std::vector<std::size_t> free_;
  const TwoMassFitOptions& options_;
};

// Start values of the dynamic terms from the read features and the data:
// undamped, |H_acc| = n^2 |w^2 - w_a^2| / (J_m |w^2 - w_r^2|).
JointParameters StartFromFeatures(const ResponseData& motor, const std::vector<char>& used, ResponseQuantity quantity,
                                  double n, const ResponseFeatures& read) {
  const double wr = Omega(read.resonance.value), wa = Omega(read.antiresonance.value);
  std::vector<double> inertia, viscous;
  for (std::size_t b = 0; b < used.size(); ++b) {
    if (!used[b]) continue;
    const double w = Omega(motor.frequency[b]);
    const Complex h_acc = motor.response[b] * std::pow(Complex(0.0, w), 2 - static_cast<int>(quantity));
    if (std::abs(w - wr) > 0.2 * wr && std::abs(w - wa) > 0.2 * wa) {
      inertia.push_back(n * n * std::abs(w * w - wa * wa) / (std::abs(w * w - wr * wr) * std::abs(h_acc)));
    }
    if (w < 0.5 * wa) viscous.push_back(std::real(n * n * Complex(0.0, w) / h_acc));  // n^2 / H_rate
  }
  JointParameters p;
  p.motor_inertia = inertia.empty() ? 1.0 : Median(inertia);
  p.link_inertia = p.motor_inertia * std::max(wr * wr / (wa * wa) - 1.0, 1e-3);
  p.stiffness = p.link_inertia * wa * wa;
  p.damping = 2.0 * 0.05 * std::sqrt(p.stiffness * p.link_inertia);
  const double total = p.motor_inertia + p.link_inertia;
  const double floor = 0.05 * total * Omega(read.band_low > 0.0 ? read.band_low : 0.1 * read.antiresonance.value);
  p.motor_viscous = std::max(viscous.empty() ? 0.0 : Median(viscous), floor);
  p.link_viscous = 0.1 * p.motor_viscous;
  return p;
}

// The delay's start: the phase of a delay turns many times over a band
// (3 ms is 430 degrees at 400 Hz), so a fit from 0 lands in a wrong turn.
// The measured phase less the start model's, r_b = arg(H_b / G_b), is
// matched by -w_b tau: the circular misfit sum w_b (1 - cos(r_b + w_b tau)),
// with w_b the bin's phase weight, is scanned over 0 .. kMaxStartDelay in
// steps that turn the band's top by 0.2 rad, and its minimum taken. This is
// the unwrapped phase slope's least squares, made robust to gaps between
// bins and to a start model's phase error near the modes.
constexpr double kMaxStartDelay = 0.02;  // [s]

template <typename Row>
double StartDelay(const ResponseData& motor, const std::vector<char>& used, const std::vector<Complex>& start_model,
                  const std::vector<Row>& rows, double band_high) {
  std::vector<double> omega, residual, weight;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    if (rows[r].link || rows[r].phase || !used[rows[r].bin]) continue;  // one row per motor bin
    const std::size_t b = rows[r].bin;
    const double phase = std::arg(motor.response[b] / start_model[r]);
    const double s = motor.phase_std.empty() ? 1.0 : motor.phase_std[b];
    if (!std::isfinite(phase) || !(s > 0.0) || !std::isfinite(s)) continue;
    omega.push_back(Omega(motor.frequency[b]));
    residual.push_back(phase);
    weight.push_back(1.0 / (s * s));
  }
  if (omega.empty() || !(band_high > 0.0)) return 0.0;
  const double step = 0.2 / Omega(band_high);
  double best = 0.0, best_cost = std::numeric_limits<double>::infinity();
  for (double tau = 0.0; tau <= kMaxStartDelay; tau += step) {
    double cost = 0.0;
    for (std::size_t i = 0; i < omega.size(); ++i) cost += weight[i] * (1.0 - std::cos(residual[i] + omega[i] * tau));
    if (cost < best_cost) best_cost = cost, best = tau;
  }
  return best;
}

// Delta-method std of f(estimates) by central differences.
FrequencyEstimate Derived(const FitResult& fit, const std::function<double(const std::vector<double>&)>& f) {
  const std::size_t np = fit.estimates.size();
  std::vector<double> x(np);
  for (std::size_t j = 0; j < np; ++j) x[j] = fit.estimates[j].value;
  FrequencyEstimate out;
  out.value = f(x);
  std::vector<double> gradient(np, 0.0);
  for (std::size_t j = 0; j < np; ++j) {
    const double h = 1e-6 * std::max(std::abs(x[j]), 1e-12);
    auto up = x, down = x;
    up[j] += h;
    down[j] -= h;
    gradient[j] = (f(up) - f(down)) / (2.0 * h);
  }
  double variance = 0.0;
  for (std::size_t i = 0; i < np; ++i) {
    for (std::size_t j = 0; j < np; ++j) variance += gradient[i] * fit.covariance[i * np + j] * gradient[j];
  }
  out.standard_error = std::sqrt(std::max(variance, 0.0));
  return out;
}

std::string TwoMassAdvice(const std::vector<std::string>& involved) {
  std::vector<std::string> advice;
  const auto has = [&](double JointParameters::*member) {
    return std::find(involved.begin(), involved.end(), KeyOf(JointParameterTable(), member)) != involved.end();
  };
  if (has(&JointParameters::motor_viscous) || has(&JointParameters::link_viscous)) {
    advice.push_back("viscous friction needs the band to reach down to where friction dominates the inertia; fix "
                     "motor_viscous/link_viscous in ‹params› and leave them out of ‹free›");
  }
  if (has(&JointParameters::damping)) {
    advice.push_back("the damping needs coherent bins around the resonance and anti-resonance");
  }
  if (std::find(involved.begin(), involved.end(), Terms()[kDelay]) != involved.end()) advice.push_back("a delay separates from damping only with phase data well above the resonance");
  return fmt::format("{}", fmt::join(advice, "; "));
}

// The free terms' indices into kTerms, refused by name when unknown or twice.
std::vector<std::size_t> FreeTerms(const std::vector<std::string>& free) {
  std::vector<std::size_t> free_terms;
  for (const auto& name : free) {
    const auto& terms = Terms();
    const auto it = std::find(terms.begin(), terms.end(), name);
    if (it == terms.end()) {
      throw OptionError(fmt::format("'{}' cannot be estimated from a frequency response (possible: {})", name,
                                    fmt::join(terms, ", ")));
    }
    const auto index = static_cast<std::size_t>(it - terms.begin());
    if (std::find(free_terms.begin(), free_terms.end(), index) != free_terms.end()) {
      throw OptionError(fmt::format("'{}' is named twice", name));
    }
    free_terms.push_back(index);
  }
  return free_terms;
}

// Start: the fixed values from the file, the free dynamic terms from the
// resonance and anti-resonance read from the data (else the file's). The
// inertias and the stiffness, when fixed, must be given (all named at once).
void StartValues(const ResponseData& motor, const JointSection& s, const std::vector<std::size_t>& free_terms,
                 double n, const TwoMassFitOptions& options, const TwoMassFitOutput& out, JointParameters& fixed,
                 JointParameters& initial) {
  const std::array<std::optional<double>, 6> given = {s.motor_inertia, s.link_inertia,  s.stiffness,
                                                      s.damping,       s.motor_viscous, s.link_viscous};
  for (std::size_t i = 0; i < kMembers.size(); ++i) fixed.*(kMembers[i]) = given[i].value_or(0.0);
  std::vector<const ParameterSpec*> needed;
  for (std::size_t i = 0; i < 3; ++i) {
    const bool is_free = std::find(free_terms.begin(), free_terms.end(), i) != free_terms.end();
    if (!is_free && !(given[i].value_or(0.0) > 0.0)) {
      needed.push_back(&FindParameter(JointParameterTable(), Terms()[i])->spec);
    }
  }
  if (!needed.empty()) {
    throw MissingValuesError("‹params›", "joint", needed, "(fixed in this fit)",
                             " (values > 0), or name them in ‹free›");
  }
  const bool read_ok = out.read.resonance.value > 0.0 && out.read.antiresonance.value > 0.0 &&
                       out.read.antiresonance.value < out.read.resonance.value;
  initial = fixed;
  if (read_ok) {
    initial = StartFromFeatures(motor, out.motor_used, options.motor_output, n, out.read);
    return;
  }
  std::vector<std::string> missing;
  for (std::size_t index : free_terms) {
    if (index != kDelay && !(given[index].value_or(0.0) > 0.0)) missing.emplace_back(Terms()[index]);
  }
  if (!missing.empty()) {
    throw IdentificationError(fmt::format(
        "no {} in the coherent band {:.4g} .. {:.4g} Hz of the motor response, so the two-mass model is not "
        "determined there ({} need start values in ‹params›, or excite across the resonance)",
        out.read.resonance.value > 0.0 ? "anti-resonance below the resonance" : "resonance peak", out.band_low,
        out.band_high, fmt::join(missing, ", ")));
  }
}

// The fitted channels: per response its log magnitude and phase over the
// used bins, each divided by its std; `measured` holds the values.
struct ResponseChannels {
  std::vector<ResponseResiduals::Row> rows;
  std::vector<FitChannel> channels;
  std::vector<std::vector<double>> measured;
  void Add(const ResponseData& data, const std::vector<char>& used, bool is_link) {
    for (bool phase : {false, true}) {
      FitChannel channel;
      channel.name = fmt::format("{} {}", is_link ? "link" : "motor", phase ? "phase" : "log magnitude");
      channel.begin = static_cast<int>(rows.size());
      std::vector<double> values;
      for (std::size_t b = 0; b < used.size(); ++b) {
        if (!used[b]) continue;
        rows.push_back({&data, b, is_link, phase});
        const double sigma = phase ? (data.phase_std.empty() ? 1.0 : data.phase_std[b])
                                   : (data.log_magnitude_std.empty() ? 1.0 : data.log_magnitude_std[b]);
        values.push_back((phase ? std::arg(data.response[b]) : std::log(std::abs(data.response[b]))) / sigma);
      }
      channel.count = static_cast<int>(values.size());
      measured.push_back(std::move(values));
      channels.push_back(channel);
    }
  }
  void Finish() {
    for (std::size_t c = 0; c < channels.size(); ++c) channels[c].measured = measured[c].data();
  }
};

// Resonance and anti-resonance of the estimates, with the delta method;
// refused when either lies outside the coherent band.
void AddFeatures(const std::vector<std::size_t>& free_terms, TwoMassFitOutput& out) {
  const auto with = [&](const std::vector<double>& x) {
    JointParameters p = out.params;
    for (std::size_t j = 0; j < free_terms.size(); ++j) {
      if (free_terms[j] != kDelay) p.*(kMembers[free_terms[j]]) = x[j];
    }
    return p;
  };
  out.resonance = Derived(out.fit, [&](const std::vector<double>& x) { return JointResonance(with(x)) / (2.0 * M_PI); });
  out.antiresonance =
      Derived(out.fit, [&](const std::vector<double>& x) { return JointAntiresonance(with(x)) / (2.0 * M_PI); });
  for (const auto& [name, f] : {std::pair<const char*, double>{"resonance", out.resonance.value},
                                {"anti-resonance", out.antiresonance.value}}) {
    if (!(f >= out.band_low && f <= out.band_high)) {
      throw IdentificationError(fmt::format("the fitted {} at {:.4g} Hz lies outside the coherent band {:.4g} .. {:.4g} "
                                            "Hz: the response does not determine the two-mass model (excite across it, "
                                            "or ‹band›)",
                                            name, f, out.band_low, out.band_high));
    }
  }
}

// A measured phase that falls away from the model linearly with frequency
// is a lag the model lacks (sampling, filters, a bus): the phase of
// measured / model over the fitted motor bins, fitted as -omega tau through
// 0 (weighted by the bins' phase std where known); a tau more than 3 std
// from 0 that turns the phase by more than 10 degrees at the band's top draws
// a warning that says to free `delay`.
void CheckLinearPhase(const ResponseData& motor, const TwoMassFitOutput& out, std::vector<std::string>& warnings) {
  double sww = 0.0, swr = 0.0, swrr = 0.0;
  int bins = 0;
  for (std::size_t b = 0; b < motor.frequency.size(); ++b) {
    if (!out.motor_used[b] || !(std::abs(out.motor_model[b]) > 0.0)) continue;
    const double omega = Omega(motor.frequency[b]);
    const double r = std::arg(motor.response[b] / out.motor_model[b]);
    const double s = motor.phase_std.empty() ? 1.0 : motor.phase_std[b];
    if (!(s > 0.0) || !std::isfinite(s) || !std::isfinite(r)) continue;
    const double w = 1.0 / (s * s);
    sww += w * omega * omega;
    swr += w * omega * r;
    swrr += w * r * r;
    ++bins;
  }
  if (bins < 3 || !(sww > 0.0)) return;
  const double tau = -swr / sww;
  // The std from the bins' own phase std, or from the scatter when unknown.
  const double scatter = motor.phase_std.empty() ? std::max(0.0, swrr - tau * tau * sww) / (bins - 1) : 1.0;
  const double tau_std = std::sqrt(scatter / sww);
  const double turn = Omega(out.band_high) * std::abs(tau);
  if (std::abs(tau) > 3.0 * tau_std && turn > 10.0 * M_PI / 180.0) {
    warnings.push_back(fmt::format(
        "phase: the measured phase falls away from the model linearly with frequency, as a delay of {:.3g} +- {:.2g} ms "
        "({:.0f} degrees at {:.4g} Hz) would: a lag the model lacks (sampling, a filter, a bus); free delay in ‹free›",
        1e3 * tau, 1e3 * tau_std, turn * 180.0 / M_PI, out.band_high));
  }
}

// A response channel the two-mass model leaves in long waves across
// frequency (fit % below kResponseFitPercent with residual lag-1 across
// bins at least kResponseWaves) misses a feature of the response: a second
// mode, a notch or filter, a lag. The generic low-fit check (50 %) lets
// a third of a response go unexplained; the intervals then rest on the
// long-run covariance of a shape error.
constexpr double kResponseFitPercent = 90.0;
constexpr double kResponseWaves = 0.5;

void CheckResponseShape(const TwoMassFitOutput& out, bool delay_free, std::vector<std::string>& warnings) {
  for (const auto& c : out.fit.channels) {
    if (!(c.fit_percent < kResponseFitPercent) || c.fit_percent < kLowFitPercent || c.autocorrelation < kResponseWaves) {
      continue;  // below 50 % the generic low-fit warning speaks
    }
    warnings.push_back(fmt::format(
        "model: {}: fitted {:.1f} % (below {:.0f} %) with residuals in long waves across frequency (lag-1 {:.2f} over "
        "{} bins): the two-mass model misses a feature of the response (a second mode, a notch or filter, a lag), and "
        "its stiffness, inertias, resonance and anti-resonance may be off by more than their std; look at the Bode "
        "plot (‹plot›), narrow ‹band› to the first mode{}",
        c.name, c.fit_percent, kResponseFitPercent, c.autocorrelation, c.samples, delay_free ? "" : ", or free delay"));
  }
}

}  // namespace

TwoMassFitOutput FitTwoMassResponse(const ResponseData& motor, const ResponseData* link, const JointSection& start,
                                    const TwoMassFitOptions& options) {
  RequireValid(options);
  const std::vector<std::size_t> free_terms = FreeTerms(options.free);
  if (free_terms.empty()) throw OptionError("no parameter to estimate");
  const double n = start.gear_ratio.value_or(1.0);
  if (!(n > 0.0) || !std::isfinite(n)) throw InputError("joint.gear_ratio must be a positive number");

  TwoMassFitOutput out;
  out.motor_used = BandBins(motor, options.Band());
  out.link_used = link != nullptr ? BandBins(*link, options.Band()) : std::vector<char>{};
  UsedBand(motor, out.motor_used, out.band_low, out.band_high);
  const auto used_count = std::count(out.motor_used.begin(), out.motor_used.end(), 1);
  if (used_count < 3) {
    throw InputError(fmt::format("the motor response has {} bins with coherence >= {} in the band: nothing to fit "
                                 "(more excitation, longer logs, or ‹band›)",
                                 used_count, options.min_coherence));
  }
  out.read = ReadResponseFeatures(motor, options.motor_output, options.Band());

  JointParameters fixed, initial;
  StartValues(motor, start, free_terms, n, options, out, fixed, initial);
  std::vector<FitParameter> parameters;
  for (std::size_t index : free_terms) {
    const double value = index == kDelay ? 0.0 : initial.*(kMembers[index]);
    FitParameter fp{Terms()[index], value, 0.0, 0.0};
    if (index == kDelay) fp.scale = 1.0 / Omega(out.band_high);
    parameters.push_back(fp);
  }

  ResponseChannels fitted;
  fitted.Add(motor, out.motor_used, false);
  if (link != nullptr) fitted.Add(*link, out.link_used, true);
  fitted.Finish();
  const std::vector<FitChannel>& channels = fitted.channels;
  const std::vector<ResponseResiduals::Row>& rows = fitted.rows;
  ResponseResiduals model(rows, fixed, n, free_terms, options);
  const auto delay_at = std::find(free_terms.begin(), free_terms.end(), kDelay);
  if (delay_at != free_terms.end()) {
    parameters[static_cast<std::size_t>(delay_at - free_terms.begin())].initial =
        StartDelay(motor, out.motor_used, ResponseResiduals(rows, initial, n, {}, options).Values(initial, 0.0), rows,
                   out.band_high);
  }
  FitOptions fit_options = options.fit;
  if (!fit_options.advice) fit_options.advice = TwoMassAdvice;
  out.fit = FitLeastSquares(model, parameters, channels, fit_options);
  out.params = fixed;
  for (std::size_t j = 0; j < free_terms.size(); ++j) {
    if (free_terms[j] == kDelay) {
      out.delay = out.fit.estimates[j].value;
    } else {
      out.params.*(kMembers[free_terms[j]]) = out.fit.estimates[j].value;
    }
  }
  std::vector<std::string> nonnegative;
  for (std::size_t index : free_terms) {
    if (index != kDelay) nonnegative.emplace_back(Terms()[index]);
  }
  const auto model_at = [&](const ResponseData& data, bool is_link) {
    std::vector<ResponseResiduals::Row> all;
    for (std::size_t b = 0; b < data.frequency.size(); ++b) all.push_back({&data, b, is_link, false});
    return ResponseResiduals(all, out.params, n, {}, options).Values(out.params, out.delay);
  };
  out.motor_model = model_at(motor, false);
  if (link != nullptr) out.link_model = model_at(*link, true);
  // Before the refusals, which carry the warnings as their context.
  if (std::find(free_terms.begin(), free_terms.end(), kDelay) == free_terms.end()) {
    CheckLinearPhase(motor, out, out.fit.warnings);
  }
  CheckResponseShape(out, delay_at != free_terms.end(), out.fit.warnings);
  std::map<std::string, double> start_values;
  for (const auto& p : parameters) start_values[p.name] = p.initial;
  RequireDetermined(out.fit, nonnegative, kMaxRelativeStd, out.fit.warnings, start_values);
  AddFeatures(free_terms, out);
  return out;
}

}  // namespace driveid
