#include "design/joint_excitation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <string>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/errors.h"

namespace driveid {
namespace {

// The dynamic terms in CalcJointResponse's gradient order.
constexpr std::array<double JointParameters::*, 6> kDynamicMembers = {
    &JointParameters::motor_inertia, &JointParameters::link_inertia, &JointParameters::stiffness,
    &JointParameters::damping,       &JointParameters::motor_viscous, &JointParameters::link_viscous};
// Lines and line x sample products the design evaluates at most.
constexpr std::size_t kMaxLines = 5000;
constexpr double kMaxWaveformWork = 2e8;
constexpr int kMaxIterations = 5000;
constexpr double kMaxLineIterations = 2e6;
constexpr double kCrestIterations = 60;
constexpr double kMaxCrestWork = 3e7;  // line x sample products of the crest-factor rounds

std::size_t TermIndex(const std::string& name) {
  std::vector<std::string> keys;
  for (const auto member : kDynamicMembers) keys.push_back(KeyOf(JointParameterTable(), member));
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (name == keys[i]) return i;
  }
  throw OptionError(fmt::format("‹free› {}: the joint design predicts the dynamic terms only ({}); "
                               "Coulomb friction and the offsets do not enter the frequency response",
                               name, fmt::join(keys, ", ")));
}

// Per line: the motor-rate response and the information per unit power share
// and per sample, Re(g_l g_l^H) / (sigma_v^2 / |H_l|^2 + sigma_u^2), over the
// relative free parameters (F = M N R^2 sum_l w_l F_l).
struct LineInformation {
  std::vector<std::complex<double>> response;
  std::vector<Eigen::MatrixXd> information;
};

LineInformation Information(const JointParameters& prior, double gear_ratio, const std::vector<std::size_t>& index,
                            const std::vector<double>& frequency, double speed_noise, double torque_noise) {
  LineInformation out;
  const auto m = static_cast<Eigen::Index>(index.size());
  for (const double f : frequency) {
    const JointResponse r = CalcJointResponse(prior, gear_ratio, 2.0 * M_PI * f, ResponseQuantity::kRate);
    Eigen::VectorXcd g(m);
    for (Eigen::Index j = 0; j < m; ++j) {
      const std::size_t term = index[static_cast<std::size_t>(j)];
      g(j) = r.motor_log_gradient[term] * (prior.*kDynamicMembers[term]);
    }
    out.response.push_back(r.motor);
    const double relative_variance = speed_noise * speed_noise / std::norm(r.motor) + torque_noise * torque_noise;
    out.information.push_back((g * g.adjoint()).real() / relative_variance);
  }
  return out;
}

Eigen::MatrixXd Weighted(const LineInformation& info, const std::vector<double>& share) {
  Eigen::MatrixXd f = Eigen::MatrixXd::Zero(info.information.front().rows(), info.information.front().cols());
  for (std::size_t l = 0; l < share.size(); ++l) f += share[l] * info.information[l];
  return f;
}

// The nuisance block (rows whose weight is 0) of a matrix.
Eigen::MatrixXd Nuisance(const Eigen::MatrixXd& f, const std::vector<Eigen::Index>& rows) {
  Eigen::MatrixXd out(rows.size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (std::size_t j = 0; j < rows.size(); ++j) out(i, j) = f(rows[i], rows[j]);
  }
  return out;
}

// Optimal power shares by multiplicative algorithms: D_s on the target rows
// of `weight` (the others nuisance; plain D when all are targets),
//   d_l = tr(F^-1 F_l) - tr(F_nn^-1 F_l,nn),  w_l <- w_l d_l / s,
// (Titterington; at the optimum max_l d_l = s, the equivalence theorem),
// or A: w_l <- w_l sqrt(tr(W F^-1 F_l F^-1)), normalised. Returns the
// iterations and max_l d_l / s.
std::vector<double> OptimalShares(const LineInformation& info, const std::string& criterion,
                                  const Eigen::VectorXd& weight, int* iterations, double* equivalence) {
  const std::size_t lines = info.information.size();
  std::vector<Eigen::Index> nuisance;
  for (Eigen::Index i = 0; i < weight.size(); ++i) {
    if (weight(i) == 0.0) nuisance.push_back(i);
  }
  const auto s = static_cast<double>(weight.size() - static_cast<Eigen::Index>(nuisance.size()));
  std::vector<double> share(lines, 1.0 / static_cast<double>(lines)), score(lines);
  // Work bounded: at most kMaxLineIterations line updates in all.
  const int most = static_cast<int>(std::min<double>(kMaxIterations, kMaxLineIterations / static_cast<double>(lines)));
  for (*iterations = 0; *iterations < most; ++*iterations) {
    const Eigen::MatrixXd total_information = Weighted(info, share);
    const Eigen::MatrixXd inverse = total_information.inverse();
    const Eigen::MatrixXd nuisance_inverse =
        nuisance.empty() ? Eigen::MatrixXd() : Nuisance(total_information, nuisance).inverse();
    double largest = 0.0, total = 0.0;
    for (std::size_t l = 0; l < lines; ++l) {
      double d = (inverse * info.information[l]).trace();
      if (!nuisance.empty()) d -= (nuisance_inverse * Nuisance(info.information[l], nuisance)).trace();
      if (criterion == "a") {
        const Eigen::MatrixXd product = inverse * info.information[l] * inverse;
        score[l] = std::sqrt(std::max(0.0, (weight.asDiagonal() * product).trace()));
      } else {
        score[l] = std::max(0.0, d) / s;
      }
      largest = std::max(largest, d / s);
    }
    *equivalence = largest;
    if (criterion != "a" && largest < 1.0 + 1e-4) break;
    for (std::size_t l = 0; l < lines; ++l) total += share[l] * score[l];
    if (!(total > 0.0)) break;
    for (std::size_t l = 0; l < lines; ++l) share[l] *= score[l] / total;
  }
  return share;
}

// Schroeder's phases for unequal powers: phi_k = -2 pi sum_{i<k} (k - i) w_i.
std::vector<double> SchroederPhases(const std::vector<double>& share) {
  std::vector<double> phase(share.size(), 0.0);
  double cumulative = 0.0, moment = 0.0;  // sum w_i and sum w_i i over i < k
  for (std::size_t k = 0; k < share.size(); ++k) {
    phase[k] = std::remainder(-2.0 * M_PI * (static_cast<double>(k) * cumulative - moment), 2.0 * M_PI);
    cumulative += share[k];
    moment += share[k] * static_cast<double>(k);
  }
  return phase;
}

// sum_l a_l cos(w_l t_i + phi_l) at one period's samples t_i = i / rate.
std::vector<double> OnePeriod(const std::vector<double>& amplitude, const std::vector<double>& phase,
                              const std::vector<double>& omega, std::size_t samples, double rate) {
  std::vector<double> waveform(samples, 0.0);
  for (std::size_t i = 0; i < samples; ++i) {
    const double t = static_cast<double>(i) / rate;
    for (std::size_t l = 0; l < amplitude.size(); ++l) {
      if (amplitude[l] > 0.0) waveform[i] += amplitude[l] * std::cos(omega[l] * t + phase[l]);
    }
  }
  return waveform;
}

double PeakOf(const std::vector<double>& waveform) {
  double peak = 0.0;
  for (const double x : waveform) peak = std::max(peak, std::abs(x));
  return peak;
}

std::vector<double> Omega(const std::vector<double>& frequency) {
  std::vector<double> omega(frequency.size());
  for (std::size_t l = 0; l < frequency.size(); ++l) omega[l] = 2.0 * M_PI * frequency[l];
  return omega;
}

// The largest rms with the injected torque within kJointTorqueMargin of its
// limit and the prior's motor speed within kJointSpeedMargin of its own, for
// the unit-rms waveform's peaks; `binding` names the limit that sets it.
double RmsWithinLimits(double unit_torque_peak, double unit_speed_peak, const JointDesignOptions& options,
                       std::string* binding) {
  const double by_torque = kJointTorqueMargin * options.max_torque / unit_torque_peak;
  const double by_speed = kJointSpeedMargin * options.max_speed / unit_speed_peak;
  if (binding) *binding = by_torque <= by_speed ? "torque" : "speed";
  return std::min(by_torque, by_speed);
}

// Phases of a lower crest factor (clipping and re-phasing: the waveform is
// clipped at 90 % of its peak and each line takes the phase of the clipped
// waveform's Fourier coefficient, amplitudes kept); the best of
// kCrestIterations, starting from Schroeder's.
std::vector<double> ReducedCrestPhases(const std::vector<double>& amplitude, std::vector<double> phase,
                                       const std::vector<double>& frequency, std::size_t samples, double rate) {
  const std::vector<double> omega = Omega(frequency);
  std::size_t active = 0;
  for (const double a : amplitude) active += a > 0.0 ? 1 : 0;
  const double work = 2.0 * static_cast<double>(samples) * static_cast<double>(std::max<std::size_t>(active, 1));
  const int iterations = static_cast<int>(std::min(kCrestIterations, kMaxCrestWork / work));
  std::vector<double> best = phase, waveform = OnePeriod(amplitude, phase, omega, samples, rate);
  double peak = PeakOf(waveform), best_peak = peak;
  for (int k = 0; k < iterations; ++k) {
    const double level = 0.9 * peak;
    for (double& x : waveform) x = std::clamp(x, -level, level);
    for (std::size_t l = 0; l < amplitude.size(); ++l) {
      if (!(amplitude[l] > 0.0)) continue;
      double re = 0.0, im = 0.0;
      for (std::size_t i = 0; i < samples; ++i) {
        const double angle = omega[l] * static_cast<double>(i) / rate;
        re += waveform[i] * std::cos(angle);
        im -= waveform[i] * std::sin(angle);
      }
      phase[l] = std::atan2(im, re);
    }
    waveform = OnePeriod(amplitude, phase, omega, samples, rate);
    peak = PeakOf(waveform);
    if (peak < best_peak) {
      best_peak = peak;
      best = phase;
    }
  }
  return best;
}

JointDesignCandidate MakeCandidate(const std::string& name, const std::vector<double>& share,
                                   const LineInformation& info, const JointDesign& design,
                                   const JointDesignOptions& options, double rms, bool reduce_crest) {
  JointDesignCandidate c;
  c.name = name;
  c.phase = SchroederPhases(share);
  for (const double w : share) c.amplitude.push_back(std::sqrt(2.0 * w));
  const auto samples = static_cast<std::size_t>(std::llround(design.period * options.rate));
  if (reduce_crest) c.phase = ReducedCrestPhases(c.amplitude, c.phase, design.frequency, samples, options.rate);
  // Peaks of the unit-rms waveform and of the prior's steady motor speed
  // (each line through H_l).
  const std::vector<double> omega = Omega(design.frequency);
  std::vector<double> speed_amplitude(share.size()), speed_phase(share.size());
  for (std::size_t l = 0; l < share.size(); ++l) {
    speed_amplitude[l] = c.amplitude[l] * std::abs(info.response[l]);
    speed_phase[l] = c.phase[l] + std::arg(info.response[l]);
  }
  const double peak_torque = PeakOf(OnePeriod(c.amplitude, c.phase, omega, samples, options.rate));
  const double peak_speed = PeakOf(OnePeriod(speed_amplitude, speed_phase, omega, samples, options.rate));
  if (!(rms > 0.0)) rms = RmsWithinLimits(peak_torque, peak_speed, options, &c.binding);
  c.rms = rms;
  for (double& a : c.amplitude) a *= rms;
  c.peak_torque = peak_torque * rms;
  c.peak_speed = peak_speed * rms;
  // F = M N R^2 / sigma^2 sum_l w_l F_l over the relative parameters.
  const double samples_per_period = static_cast<double>(samples);
  const double settled = design.periods >= 3 ? design.periods - 1 : design.periods;
  const Eigen::MatrixXd information = settled * samples_per_period * rms * rms * Weighted(info, share);
  const Eigen::MatrixXd relative = information.inverse();
  const auto m = static_cast<Eigen::Index>(design.free.size());
  c.covariance.resize(m, m);
  double log_sum = 0.0;
  for (Eigen::Index i = 0; i < m; ++i) {
    for (Eigen::Index j = 0; j < m; ++j) {
      c.covariance(i, j) = relative(i, j) * design.prior[static_cast<std::size_t>(i)] * design.prior[static_cast<std::size_t>(j)];
    }
    c.predicted_std.push_back(std::sqrt(c.covariance(i, i)));
    log_sum += 0.5 * std::log(relative(i, i));
  }
  c.geometric_mean_relative_std = std::exp(log_sum / static_cast<double>(m));
  return c;
}

}  // namespace

bool JointDesignOptions::IsValid(std::string* error) const {
  const auto fail = [error](std::string text) {
    if (error) *error = std::move(text);
    return false;
  };
  if (!(rate > 0.0) || !std::isfinite(rate) || rate > 1e6) return fail(fmt::format("‹rate› {}: (0, 1e6] Hz", rate));
  const double per_period = period * rate;
  if (!(period > 0.0) || !std::isfinite(period) || per_period < 16.0 || per_period > 1e7 ||
      std::abs(per_period - std::round(per_period)) > 1e-6 * per_period) {
    return fail(fmt::format("‹period› {} s: a whole number of samples at ‹rate›, at least 16", period));
  }
  if (!(duration >= 5.0 * period) || !std::isfinite(duration) || duration * rate > 5e7) {
    return fail(fmt::format("‹duration› {} s: at least 5 periods of {} s (the first settles; the estimate needs 4), at "
                            "most 5e7 samples",
                            duration, period));
  }
  if (!(band_low >= 0.0) || !(band_high > band_low) || !(band_high < 0.5 * rate)) {
    return fail(fmt::format("‹band› {},{}: 0 <= LO < HI < rate/2", band_low, band_high));
  }
  if (!(max_torque > 0.0) || !std::isfinite(max_torque)) return fail(fmt::format("‹max_torque› {}: > 0", max_torque));
  if (!(max_speed > 0.0) || !std::isfinite(max_speed)) return fail(fmt::format("‹max_speed› {}: > 0", max_speed));
  if (!(noise > 0.0) || !std::isfinite(noise)) return fail(fmt::format("‹noise› {}: > 0 rad/s", noise));
  if (!(torque_noise >= 0.0) || !std::isfinite(torque_noise)) {
    return fail(fmt::format("‹torque_noise› {}: >= 0 N m", torque_noise));
  }
  if (criterion != "d" && criterion != "a") return fail(fmt::format("‹criterion› {}: d or a", criterion));
  if (!(spread >= 0.0 && spread < 1.0)) return fail(fmt::format("‹spread› {}: in [0, 1)", spread));
  if (free.empty()) return fail("‹free›: no parameter to design for");
  return true;
}

JointDesign DesignJointExcitation(const JointParameters& prior, double gear_ratio, const JointDesignOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw OptionError(error);
  JointDesign design;
  design.free = options.free;
  design.period = options.period;
  design.noise = options.noise;
  design.torque_noise = options.torque_noise;
  design.gear_ratio = gear_ratio;
  design.periods = static_cast<int>(std::floor(options.duration / options.period + 1e-9));
  std::vector<std::size_t> index;
  for (const auto& name : options.free) {
    index.push_back(TermIndex(name));
    const double value = prior.*kDynamicMembers[index.back()];
    if (!(value > 0.0) || !std::isfinite(value)) {
      throw InputError(fmt::format("‹params›: joint.{} = {}: the design needs a positive prior value for a free "
                                   "parameter (its std is relative to it)",
                                   name, value));
    }
    design.prior.push_back(value);
  }
  const auto first = static_cast<long>(std::max(1.0, std::ceil(options.band_low * options.period - 1e-9)));
  const auto last = static_cast<long>(std::floor(options.band_high * options.period + 1e-9));
  const auto lines = static_cast<std::size_t>(std::max(0L, last - first + 1));
  if (lines < 2) throw OptionError(fmt::format("‹band› {},{}: fewer than 2 lines of the {} s period in it",
                                               options.band_low, options.band_high, options.period));
  if (lines > kMaxLines || static_cast<double>(lines) * options.period * options.rate > kMaxWaveformWork) {
    throw OptionError(fmt::format("‹band› {},{}: {} lines of the {} s period: at most {} (and lines x samples per "
                                  "period at most {:g}); narrow the band or shorten the period",
                                  options.band_low, options.band_high, lines, options.period, kMaxLines,
                                  kMaxWaveformWork));
  }
  for (long l = first; l <= last; ++l) design.frequency.push_back(static_cast<double>(l) / options.period);
  const LineInformation info =
      Information(prior, gear_ratio, index, design.frequency, options.noise, options.torque_noise);
  const std::vector<double> uniform(lines, 1.0 / static_cast<double>(lines));
  const Eigen::MatrixXd flat = Weighted(info, uniform);
  const double scale = flat.cwiseAbs().maxCoeff();
  if (!std::isfinite(scale) || !(scale > 0.0) || !(scale < 1e200) || !(scale > 1e-200)) {
    throw OptionError(fmt::format("‹noise› {} rad/s and ‹torque_noise› {} N m: information out of range ({:g}): give "
                                  "the noise per sample in the log's units",
                                  options.noise, options.torque_noise, scale));
  }
  Eigen::FullPivLU<Eigen::MatrixXd> lu(flat / scale);
  if (lu.rank() < static_cast<Eigen::Index>(index.size())) {
    throw InputError("the band's lines do not determine the free parameters together (their information is "
                     "singular): widen ‹band› or fix a parameter");
  }
  Eigen::VectorXd weight = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(index.size()));
  if (!options.targets.empty()) {
    weight.setZero();
    for (const auto& target : options.targets) {
      const auto found = std::find(options.free.begin(), options.free.end(), target);
      if (found == options.free.end()) throw OptionError(fmt::format("‹target› {}: not a free parameter", target));
      weight(found - options.free.begin()) = 1.0;
    }
  }
  std::vector<double> share = OptimalShares(info, options.criterion, weight, &design.iterations, &design.equivalence);
  for (double& w : share) w = (1.0 - options.spread) * w + options.spread / static_cast<double>(lines);
  design.designed = MakeCandidate("designed", share, info, design, options, 0.0, true);
  design.naive = MakeCandidate("default multisine", uniform, info, design, options, design.designed.rms, false);
  design.naive_rms_at_limits = RmsWithinLimits(design.naive.peak_torque / design.naive.rms,
                                               design.naive.peak_speed / design.naive.rms, options, nullptr);
  return design;
}

std::vector<double> SampleJointExcitation(const JointDesign& design, const JointDesignCandidate& candidate,
                                          double rate, double duration) {
  const auto samples = static_cast<std::size_t>(std::llround(duration * rate));
  const auto per_period = static_cast<std::size_t>(std::llround(design.period * rate));
  const std::vector<double> one = OnePeriod(candidate.amplitude, candidate.phase, Omega(design.frequency), per_period, rate);
  std::vector<double> out(samples);
  for (std::size_t i = 0; i < samples; ++i) out[i] = one[i % per_period];
  return out;
}

}  // namespace driveid
