#include "control/cdrive_controller.h"

#include <algorithm>
#include <cmath>

#include "core/option_check.h"

namespace driveid {
namespace {
double DeadZoneSign(double value, double dead_zone) noexcept {
  return std::abs(value) < dead_zone ? 0.0 : Signum(value);
}
}  // namespace

bool CDriveControlSettings::IsValid(std::string* error) const {
  return OptionCheck(error)
      .Require(Finite(proportional_gain), "cdrive.control.K_P", proportional_gain, "finite")
      .Require(Finite(second_gain), "cdrive.control.K_I", second_gain, "finite")
      .Require(Finite(derivative_gain), "cdrive.control.K_D", derivative_gain, "finite")
      .Require(NotNegative(dead_zone), "cdrive.control.dead_zone", dead_zone, ">= 0")
      .Require(Positive(rate_limit), "cdrive.control.rate_limit", rate_limit, "> 0")
      .Require(Positive(sample_time), "cdrive.control.sample_time", sample_time, "> 0")
      .Require(Positive(encoder_counts), "cdrive.control.encoder_counts", encoder_counts, "> 0")
      .Require(Positive(velocity_window), "cdrive.control.velocity_window", velocity_window, "> 0")
      .Require(velocity_window >= sample_time, "cdrive.control.velocity_window", velocity_window,
               "velocity window >= sample time");
}

const char* ControlLawName(ControlLaw law) {
  switch (law) {
    case ControlLaw::kPI: return "PI";
    case ControlLaw::kPD: return "PD";
    case ControlLaw::kPID: return "PID";
  }
  return "PI";
}

FrictionCompensator::FrictionCompensator(const CDriveParameters& params, double dead_zone, double rate_limit,
                                         double sample_time) noexcept
    : beta_(params.viscous_motor), gamma_(params.viscous_collar), delta_(params.coulomb_motor),
      eta_(params.coulomb_collar), dead_zone_(dead_zone), max_step_(rate_limit * sample_time) {}

void FrictionCompensator::Reset() noexcept { limited_.fill(0.0); }

Vector2 FrictionCompensator::Update(double rate_left, double rate_right) noexcept {
  const double difference = rate_left - rate_right;
  const double targets[3] = {DeadZoneSign(rate_left, dead_zone_), DeadZoneSign(rate_right, dead_zone_),
                             DeadZoneSign(difference, dead_zone_)};
  for (int i = 0; i < 3; ++i) {
    limited_[static_cast<std::size_t>(i)] += std::clamp(targets[i] - limited_[static_cast<std::size_t>(i)], -max_step_, max_step_);
  }
  return {beta_ * rate_left + delta_ * limited_[0] + 0.5 * gamma_ * difference + eta_ * limited_[2],
          beta_ * rate_right + delta_ * limited_[1] - 0.5 * gamma_ * difference - eta_ * limited_[2]};
}

CDriveController::CDriveController(const CDriveParameters& params, const CDriveControlSettings& settings) noexcept
    : settings_(settings),
      compensator_(params, settings.dead_zone, settings.rate_limit, settings.sample_time),
      window_periods_(std::clamp(static_cast<int>(std::lround(settings.velocity_window / settings.sample_time)), 1,
                                 kHistory - 1)) {}

void CDriveController::Reset() noexcept {
  compensator_.Reset();
  head_ = 0;
  filled_ = 0;
  integral_ = {0.0, 0.0};
  rate_ = {0.0, 0.0};
}

Vector2 CDriveController::Update(const Vector2& reference_angle, const Vector2& reference_rate,
                                 const Vector2& encoder_angle) noexcept {
  // Encoder velocity: backward difference over the window (shorter at start-up).
  history_[static_cast<std::size_t>(head_)] = encoder_angle;
  const int span = std::min(filled_, window_periods_);
  if (span > 0) {
    const Vector2& old = history_[static_cast<std::size_t>((head_ - span + kHistory) % kHistory)];
    const double dt = span * settings_.sample_time;
    rate_ = {(encoder_angle[0] - old[0]) / dt, (encoder_angle[1] - old[1]) / dt};
  }
  head_ = (head_ + 1) % kHistory;
  filled_ = std::min(filled_ + 1, kHistory);

  const Vector2 compensation = compensator_.Update(rate_[0], rate_[1]);
  Vector2 torque = Vector2::Zero();
  for (std::size_t i = 0; i < 2; ++i) {
    const double error = reference_angle[i] - encoder_angle[i];
    const double error_rate = reference_rate[i] - rate_[i];
    double feedback = settings_.proportional_gain * error;
    switch (settings_.law) {
      case ControlLaw::kPI:
        integral_[i] += error * settings_.sample_time;
        feedback += settings_.second_gain * integral_[i];
        break;
      case ControlLaw::kPD:
        feedback += settings_.second_gain * error_rate;
        break;
      case ControlLaw::kPID:
        integral_[i] += error * settings_.sample_time;
        feedback += settings_.second_gain * integral_[i] + settings_.derivative_gain * error_rate;
        break;
    }
    torque[i] = feedback + compensation[i];
  }
  return torque;
}

double QuantizeEncoder(double angle, double counts_per_revolution) noexcept {
  const double quantum = 2.0 * M_PI / counts_per_revolution;
  return std::floor(angle / quantum) * quantum;
}

}  // namespace driveid
