// Feedback gains for an axis from its feed-forward model (issue 37;
// docs/models.md#feedback-gains once the command lands): the plant of the
// feed-forward law without its static terms, u = Kv v + Ka a, i.e.
//   v' = -(Kv/Ka) v + u/Ka            (velocity loop, state v)
//   x' = v, v' = -(Kv/Ka) v + u/Ka    (position loop, state [x, v]),
// discretised with a zero-order hold at the controller's period T, and the
// discrete LQR of Bryson's rule: Q = diag(1/e_max^2), R = 1/u_max^2 —
// WPILib SysId's feedback analysis. A measurement delay d is compensated as
// SysId does: K (A - B K)^(d/T).
#pragma once

#include <string>
#include <vector>

#include "models/feedback.h"

namespace driveid {

struct LqrSettings {
  double period = 0.02;               ///< T [s]
  double max_position_error = 1.0;    ///< [position unit]
  double max_velocity_error = 1.5;    ///< [position unit/s]
  double max_effort = 7.0;            ///< [effort unit, e.g. V]
  double delay = 0.0;                 ///< measurement delay [s]
  /// Period, tolerances and effort > 0, delay >= 0 (finite).
  bool IsValid(std::string* error) const;
};

struct FeedbackGains {
  double kp = 0.0;  ///< [effort / (position or velocity unit)]
  double kd = 0.0;  ///< position loop only [effort s / position unit]
};

/// A motor controller's conventions for its gains, as WPILib SysId's
/// presets state them: the gain is K x output_factor (output units per
/// volt), divided by velocity_time_factor for a velocity loop (its rate
/// per 100 ms or per minute), and kd divided by the period unless the
/// controller normalises its derivative by time.
struct ControllerPreset {
  const char* name;
  double output_factor;         ///< controller output per volt (1: volts; 1/12: duty; 1023/12: Talon SRX)
  double velocity_time_factor;  ///< controller's rate unit in seconds (0.1: per 100 ms; 60: per minute)
  double period;                ///< [s]
  bool normalized;              ///< kd per second (true) or per loop period (false)
  double delay;                 ///< velocity measurement delay [s] (moving-average and finite-difference filters)
  const char* description;
  /// The position unit the controller's gains are in: "" any (the log's),
  /// "rotation" (Phoenix 6; REV with its conversion factor 1), "sensor unit"
  /// (Phoenix 5: encoder counts, which only the user knows).
  const char* native_position = "";
};

/// Rotations per `unit` for an angle unit (rad, Radians, deg, Degrees,
/// rotation, Rotations, rev, turn, ...; case and plural ignored), else 0.
double RotationsPerUnit(const std::string& unit);

/// The presets, first the default (WPILib PIDController).
const std::vector<ControllerPreset>& ControllerPresets();
/// The preset named `name`, or nullptr.
const ControllerPreset* FindControllerPreset(const std::string& name);

enum class FeedbackLoop { kVelocity, kPosition };

/// What a gain computation needs beyond Kv and Ka: the LQR settings and
/// the controller's conventions; `conversion` = controller units per log
/// position unit (e.g. encoder counts per rotation).
struct GainRequest {
  FeedbackLoop loop = FeedbackLoop::kVelocity;
  LqrSettings lqr;
  double output_factor = 1.0;
  double velocity_time_factor = 1.0;
  bool normalized = true;
  double conversion = 1.0;
  /// Positive conversion factors, and the LQR settings'.
  bool IsValid(std::string* error) const;
};

/// The controller's gains as SysId computes them, in the controller's
/// units. Ka below 1e-7 (no effort to accelerate): velocity gains are 0;
/// the position loop treats the velocity as the input and returns Kv x its
/// LQR gain. Throws std::invalid_argument for Kv < 0, Ka < 0 or bad settings.
FeedbackGains ControllerGains(double kv, double ka, const GainRequest& request);

/// Gains with their uncertainty from (Kv, Ka) with stds and correlation.
/// kp is strongly concave in Ka (a Ka 25 % low raises kp far more than 25 %
/// high lowers it), so a first-order std does not describe it: the gains are
/// computed at kSampledGainPoints points of the bivariate normal of (Kv, Ka)
/// (a Halton sequence in bases 2 and 3 through Box-Muller: deterministic and
/// the same on every machine; Kv and Ka cut at 0, their physical bound), and
/// the 95 % interval is the 2.5 and 97.5 % points of those gains, the std
/// their standard deviation. `value` is the gain at the estimates.
struct GainUncertainty {
  FeedbackGains value;
  FeedbackGains standard_error;
  FeedbackGains ci95_low, ci95_high;
};
inline constexpr int kSampledGainPoints = 512;
GainUncertainty SampleGains(double kv, double kv_std, double ka, double ka_std, double correlation,
                            const GainRequest& request);

/// Velocity loop: kp on the velocity error. Kv >= 0, Ka > 0; throws
/// std::invalid_argument otherwise.
FeedbackGains VelocityLqr(double kv, double ka, const LqrSettings& s);

/// Position loop: kp on the position error, kd on the velocity error.
FeedbackGains PositionLqr(double kv, double ka, const LqrSettings& s);

/// The unit of a gain in a section (e.g. "V s/Radians"), or "controller units".
std::string FeedbackGainUnit(const FeedbackController& feedback, const std::string& key);

}  // namespace driveid
