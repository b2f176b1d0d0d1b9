#include "control/feedback_gains.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>
#include <fmt/format.h>
#include <unsupported/Eigen/MatrixFunctions>

#include "core/errors.h"
#include "core/option_check.h"

namespace driveid {
namespace {

void Check(double kv, double ka, const LqrSettings& s) {
  RequireValid(s);
  if (!(ka > 0.0) || !(kv >= 0.0) || !std::isfinite(kv) || !std::isfinite(ka)) {
    throw InputError(fmt::format("LQR: Kv = {}, Ka = {}: Kv >= 0 and Ka > 0 are required", kv, ka));
  }
}

// Zero-order-hold discretisation of (A, B) at T through the exponential of
// the augmented matrix [[A, B], [0, 0]].
void Discretise(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double t, Eigen::MatrixXd& ad, Eigen::MatrixXd& bd) {
  const Eigen::Index n = a.rows(), m = b.cols();
  Eigen::MatrixXd augmented = Eigen::MatrixXd::Zero(n + m, n + m);
  augmented.topLeftCorner(n, n) = a * t;
  augmented.topRightCorner(n, m) = b * t;
  const Eigen::MatrixXd e = augmented.exp();
  ad = e.topLeftCorner(n, n);
  bd = e.topRightCorner(n, m);
}

// The discrete algebraic Riccati equation by iteration of the Riccati
// difference equation to its fixed point (stabilisable, small systems).
Eigen::MatrixXd Riccati(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const Eigen::MatrixXd& q,
                        const Eigen::MatrixXd& r) {
  Eigen::MatrixXd p = q;
  for (int i = 0; i < 100000; ++i) {
    const Eigen::MatrixXd gain = (r + b.transpose() * p * b).ldlt().solve(b.transpose() * p * a);
    const Eigen::MatrixXd next = q + a.transpose() * p * (a - b * gain);
    const double change = (next - p).norm();
    p = 0.5 * (next + next.transpose());
    if (change <= 1e-13 * std::max(1.0, p.norm())) break;
  }
  return p;
}

Eigen::MatrixXd Gain(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const Eigen::MatrixXd& q,
                     const Eigen::MatrixXd& r, const LqrSettings& s) {
  const Eigen::MatrixXd p = Riccati(a, b, q, r);
  Eigen::MatrixXd k = (r + b.transpose() * p * b).ldlt().solve(b.transpose() * p * a);
  if (s.delay > 0.0) {
    // The state the measurement lags behind, predicted over the delay.
    const Eigen::MatrixXd closed = a - b * k;
    k = k * closed.pow(s.delay / s.period);
  }
  return k;
}

}  // namespace

FeedbackGains VelocityLqr(double kv, double ka, const LqrSettings& s) {
  Check(kv, ka, s);
  Eigen::MatrixXd a(1, 1), b(1, 1), ad, bd;
  a << -kv / ka;
  b << 1.0 / ka;
  Discretise(a, b, s.period, ad, bd);
  Eigen::MatrixXd q(1, 1), r(1, 1);
  q << 1.0 / (s.max_velocity_error * s.max_velocity_error);
  r << 1.0 / (s.max_effort * s.max_effort);
  return {Gain(ad, bd, q, r, s)(0, 0), 0.0};
}

FeedbackGains PositionLqr(double kv, double ka, const LqrSettings& s) {
  Check(kv, ka, s);
  Eigen::MatrixXd a(2, 2), b(2, 1), ad, bd;
  a << 0.0, 1.0, 0.0, -kv / ka;
  b << 0.0, 1.0 / ka;
  Discretise(a, b, s.period, ad, bd);
  Eigen::MatrixXd q = Eigen::MatrixXd::Zero(2, 2), r(1, 1);
  q(0, 0) = 1.0 / (s.max_position_error * s.max_position_error);
  q(1, 1) = 1.0 / (s.max_velocity_error * s.max_velocity_error);
  r << 1.0 / (s.max_effort * s.max_effort);
  const Eigen::MatrixXd k = Gain(ad, bd, q, r, s);
  return {k(0, 0), k(0, 1)};
}

const std::vector<ControllerPreset>& ControllerPresets() {
  // SysId's presets (docs/models.md#feedback-gains): delays from the
  // controllers' velocity filters, (N - 1)/2 T for an N-tap moving average
  // plus T/2 for a backward difference over T.
  static const std::vector<ControllerPreset> kPresets = {
      {"wpilib", 1.0, 1.0, 0.020, true, 0.0, "WPILib PIDController on the roboRIO: volts, the log's unit, 20 ms", ""},
      {"ctre-phoenix6", 1.0, 1.0, 0.001, true, 0.001, "CTRE Phoenix 6 (Talon FX): volts, rotations, 1 ms, 1 ms filter",
       "rotation"},
      {"ctre-phoenix5", 1023.0 / 12.0, 0.1, 0.001, false, 0.0815,
       "CTRE Phoenix 5 (Talon SRX/FX): 1023 per 12 V, sensor units (conversion given), rate per 100 ms, 1 ms, 81.5 ms "
       "filter",
       "sensor unit"},
      {"rev-neo", 1.0 / 12.0, 60.0, 0.001, false, 0.112,
       "REV Spark MAX with the NEO's built-in encoder: duty cycle, rotations, rate per minute, 1 ms, 112 ms filter",
       "rotation"},
      {"rev-external", 1.0 / 12.0, 60.0, 0.001, false, 0.0815,
       "REV Spark MAX with an external encoder: duty cycle, rotations, rate per minute, 1 ms, 81.5 ms filter",
       "rotation"},
  };
  return kPresets;
}

double RotationsPerUnit(const std::string& unit) {
  std::string u;
  for (char c : unit) {
    if (c != ' ') u += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  if (u.size() > 1 && u.back() == 's') u.pop_back();
  if (u == "rad" || u == "radian") return 1.0 / (2.0 * M_PI);
  if (u == "deg" || u == "degree") return 1.0 / 360.0;
  if (u == "rotation" || u == "rot" || u == "rev" || u == "revolution" || u == "turn") return 1.0;
  return 0.0;
}

const ControllerPreset* FindControllerPreset(const std::string& name) {
  for (const auto& preset : ControllerPresets()) {
    if (name == preset.name) return &preset;
  }
  return nullptr;
}

bool LqrSettings::IsValid(std::string* error) const {
  return OptionCheck(error)
      .Require(Positive(period), "‹period›", period, "period > 0 s")
      .Require(Positive(max_position_error), "‹max_position_error›", max_position_error, "> 0")
      .Require(Positive(max_velocity_error), "‹max_velocity_error›", max_velocity_error, "> 0")
      .Require(Positive(max_effort), "‹max_effort›", max_effort, "> 0")
      .Require(NotNegative(delay), "‹delay›", delay, "delay >= 0 s");
}

bool GainRequest::IsValid(std::string* error) const {
  return OptionCheck(error)
      .Require(Positive(output_factor), "output factor", output_factor, "> 0")
      .Require(Positive(velocity_time_factor), "velocity time factor", velocity_time_factor, "> 0")
      .Require(Positive(conversion), "‹conversion›", conversion, "> 0")
      .Nested(lqr);
}

FeedbackGains ControllerGains(double kv, double ka, const GainRequest& request) {
  const LqrSettings& s = request.lqr;
  RequireValid(request);
  if (!(ka >= 0.0)) throw InputError(fmt::format("gains: Ka = {}: Ka >= 0 is required", ka));
  const double scale = request.output_factor / request.conversion;
  if (ka < 1e-7) {
    Check(kv, 1.0, s);
    if (request.loop == FeedbackLoop::kVelocity) return {0.0, 0.0};
    // The velocity follows the effort at once: x' = u, a pure integrator.
    Eigen::MatrixXd a(1, 1), b(1, 1), ad, bd, q(1, 1), r(1, 1);
    a << 0.0;
    b << 1.0;
    Discretise(a, b, s.period, ad, bd);
    q << 1.0 / (s.max_position_error * s.max_position_error);
    r << 1.0 / (s.max_velocity_error * s.max_velocity_error);
    return {kv * Gain(ad, bd, q, r, s)(0, 0) * scale, 0.0};
  }
  if (request.loop == FeedbackLoop::kVelocity) {
    return {VelocityLqr(kv, ka, s).kp * scale / request.velocity_time_factor, 0.0};
  }
  const FeedbackGains k = PositionLqr(kv, ka, s);
  return {k.kp * scale, k.kd * scale / (request.normalized ? 1.0 : s.period)};
}

namespace {

// The radical inverse of `index` in `base`: the Halton sequence's term.
double RadicalInverse(int index, int base) {
  double result = 0.0, scale = 1.0 / base;
  for (int i = index; i > 0; i /= base, scale /= base) result += (i % base) * scale;
  return result;
}

// The q-quantile of sorted values (linear between order statistics).
double Quantile(const std::vector<double>& sorted, double q) {
  const double position = q * static_cast<double>(sorted.size() - 1);
  const auto below = static_cast<std::size_t>(position);
  const std::size_t above = std::min(below + 1, sorted.size() - 1);
  return sorted[below] + (position - static_cast<double>(below)) * (sorted[above] - sorted[below]);
}

}  // namespace

GainUncertainty SampleGains(double kv, double kv_std, double ka, double ka_std, double correlation,
                            const GainRequest& request) {
  GainUncertainty out;
  out.value = ControllerGains(kv, ka, request);
  out.ci95_low = out.ci95_high = out.value;
  if (!(kv_std > 0.0) && !(ka_std > 0.0)) return out;
  const double rho = std::clamp(correlation, -1.0, 1.0), across = std::sqrt(std::max(0.0, 1.0 - rho * rho));
  std::vector<double> kp, kd;
  kp.reserve(kSampledGainPoints);
  kd.reserve(kSampledGainPoints);
  for (int i = 1; i <= kSampledGainPoints; ++i) {
    // Box-Muller of the point (u1, u2) of the unit square (never 0).
    const double u1 = RadicalInverse(i, 2), u2 = RadicalInverse(i, 3);
    const double radius = std::sqrt(-2.0 * std::log(u1)), angle = 2.0 * M_PI * u2;
    const double z1 = radius * std::cos(angle), z2 = radius * std::sin(angle);
    const double kv_i = std::max(0.0, kv + kv_std * z1);
    const double ka_i = std::max(0.0, ka + ka_std * (rho * z1 + across * z2));
    const FeedbackGains g = ControllerGains(kv_i, ka_i, request);
    kp.push_back(g.kp);
    kd.push_back(g.kd);
  }
  const auto summarise = [](std::vector<double>& values, double& std, double& low, double& high) {
    double mean = 0.0, square = 0.0;
    for (double v : values) mean += v;
    mean /= static_cast<double>(values.size());
    for (double v : values) square += (v - mean) * (v - mean);
    std = std::sqrt(square / static_cast<double>(values.size() - 1));
    std::sort(values.begin(), values.end());
    low = Quantile(values, 0.025);
    high = Quantile(values, 0.975);
  };
  summarise(kp, out.standard_error.kp, out.ci95_low.kp, out.ci95_high.kp);
  summarise(kd, out.standard_error.kd, out.ci95_low.kd, out.ci95_high.kd);
  // The interval holds the estimate's own gain (a sample of 512 points
  // could miss it only where the spread is below its resolution).
  out.ci95_low.kp = std::min(out.ci95_low.kp, out.value.kp), out.ci95_high.kp = std::max(out.ci95_high.kp, out.value.kp);
  out.ci95_low.kd = std::min(out.ci95_low.kd, out.value.kd), out.ci95_high.kd = std::max(out.ci95_high.kd, out.value.kd);
  return out;
}

std::string FeedbackGainUnit(const FeedbackController& f, const std::string& key) {
  const ControllerPreset* preset = FindControllerPreset(f.preset);
  const bool own_units = !preset || (preset->output_factor == 1.0 && preset->velocity_time_factor == 1.0);
  const std::string effort = own_units ? f.effort_unit : std::string("output (") + f.preset + ")";
  const std::string position = f.position_unit;
  // The controller's rate unit: per second, per 100 ms (Phoenix 5), per
  // minute (REV): a velocity gain is output per (position per that time).
  const double per = preset ? preset->velocity_time_factor : 1.0;
  const std::string time = per == 1.0 ? "s" : per == 60.0 ? "min" : per == 0.1 ? "(100 ms)" : fmt::format("({:g} s)", per);
  if (f.loop == "velocity" && key == kGainKp) return fmt::format("{} {}/{}", effort, time, position);
  if (f.loop == "position" && key == kGainKp) return fmt::format("{}/{}", effort, position);
  if (f.loop == "position" && key == kGainKd) {
    return preset && !preset->normalized ? fmt::format("{} period/{}", effort, position)
                                         : fmt::format("{} s/{}", effort, position);
  }
  if (f.loop == "speed" && key == kGainKp) return fmt::format("{} s/{}", f.effort_unit, position);
  if (f.loop == "speed" && key == kGainKi) return fmt::format("{}/{}", f.effort_unit, position);
  return "";
}

}  // namespace driveid
