// The C-drive controller of seed 001 (sections IV.C-E; docs/models.md#c-drive), per motor
// at a fixed period: position feedback on 13-bit encoder counts plus the
// friction compensation of eq. (31),
//   tau_L = beta w_L + delta RL{sgn[DZ(w_L)]} + gamma/2 (w_L - w_R) + eta RL{sgn[DZ(w_L - w_R)]}
//   tau_R = beta w_R + delta RL{sgn[DZ(w_R)]} + gamma/2 (w_R - w_L) + eta RL{sgn[DZ(w_R - w_L)]}
// where w is the encoder velocity (backward difference over velocity_window),
// DZ zeroes |x| < dead_zone and RL limits how fast each unit sign term may
// change (rate_limit per second). The feedback law follows `law`:
//   PI:  K_P e + K_I sum(e dt);  PD: K_P e + K_I de/dt;  PID: K_P e + K_I sum(e dt) + K_D de/dt,
// with e = psi_ref - psi_measured and de/dt = psi_ref' - w.
//
// Real-time safe: no allocation, no exceptions and no I/O in Update; all
// state lives in fixed-size members. A controller can link this directly.
#pragma once

#include <array>

#include "control/cdrive_control_settings.h"
#include "models/cdrive.h"

namespace driveid {

/// Eq. (31) alone: torques that compensate the modelled dissipation at the
/// (estimated) motor rates. Keeps the rate-limiter state between calls.
class FrictionCompensator {
 public:
  FrictionCompensator(const CDriveParameters& params, double dead_zone, double rate_limit, double sample_time) noexcept;
  void Reset() noexcept;
  /// Compensation torques [N m] for motor rates w_L, w_R [rad/s]; call once per period.
  Vector2 Update(double rate_left, double rate_right) noexcept;

 private:
  double beta_, gamma_, delta_, eta_;
  double dead_zone_, max_step_;
  std::array<double, 3> limited_{};  // RL outputs: sgn L, sgn R, sgn(L - R)
};

class CDriveController {
 public:
  CDriveController(const CDriveParameters& params, const CDriveControlSettings& settings) noexcept;
  void Reset() noexcept;
  /// One period: references (angle, rate) and encoder angles -> motor torques.
  Vector2 Update(const Vector2& reference_angle, const Vector2& reference_rate, const Vector2& encoder_angle) noexcept;
  /// Encoder velocity estimate of the last Update [rad/s].
  const Vector2& estimated_rate() const noexcept { return rate_; }

  static constexpr int kHistory = 256;  ///< longest velocity window in periods

 private:
  CDriveControlSettings settings_;
  FrictionCompensator compensator_;
  int window_periods_;
  std::array<Vector2, kHistory> history_{};
  int head_ = 0;
  int filled_ = 0;
  Vector2 integral_ = Vector2::Zero();
  Vector2 rate_ = Vector2::Zero();
};

/// Encoder reading: the angle rounded down to whole counts.
double QuantizeEncoder(double angle, double counts_per_revolution) noexcept;

}  // namespace driveid
