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

GainUncertainty PropagateGains(double kv, double kv_std, double ka, double ka_std, double correlation,
                               const GainRequest& request) {
  GainUncertainty out;
  out.value = ControllerGains(kv, ka, request);
  // Central differences, steps a thousandth of each std (or of the value).
  const auto derivative = [&](bool of_ka) {
    const double base = of_ka ? ka : kv, spread = of_ka ? ka_std : kv_std;
    const double h = std::max(1e-3 * spread, 1e-6 * std::abs(base));
    if (!(h > 0.0)) return FeedbackGains{0.0, 0.0};
    const double low = of_ka ? std::max(0.0, ka - h) : std::max(0.0, kv - h), high = base + h;
    const FeedbackGains a = of_ka ? ControllerGains(kv, low, request) : ControllerGains(low, ka, request);
    const FeedbackGains b = of_ka ? ControllerGains(kv, high, request) : ControllerGains(high, ka, request);
    return FeedbackGains{(b.kp - a.kp) / (high - low), (b.kd - a.kd) / (high - low)};
  };
  const FeedbackGains d_kv = derivative(false), d_ka = derivative(true);
  const auto combine = [&](double g_kv, double g_ka) {
    const double variance = g_kv * g_kv * kv_std * kv_std + g_ka * g_ka * ka_std * ka_std +
                            2.0 * correlation * g_kv * g_ka * kv_std * ka_std;
    return std::sqrt(std::max(0.0, variance));
  };
  out.standard_error = {combine(d_kv.kp, d_ka.kp), combine(d_kv.kd, d_ka.kd)};
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
