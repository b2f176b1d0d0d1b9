// The feedback controller section of a parameter file (docs/models.md#feedback-gains),
// written by `drivetrain-fit gains`:
//   velocity loop  u = kp (v_ref - v)
//   position loop  u = kp (q_ref - q) + kd (v_ref - v)
//   speed loop     C(s) = numerator(s) / denominator(s) on the motor-shaft
//                  speed error (a PI with a notch at the resonance),
// in the controller's units (the preset's, docs/models.md#feedback-gains),
// each gain with the standard error propagated from the parameter file's
// covariance; the design's settings and margins beside them.
#pragma once

#include <array>
#include <limits>
#include <string>
#include <vector>

namespace driveid {

/// The loops `gains` designs.
inline constexpr std::array<const char*, 3> kFeedbackLoops = {"velocity", "position", "speed"};

/// The keys a feedback section may hold besides loop, preset, units and
/// the speed loop's polynomials, in the order written, with their units
/// ("effort", "position" stand for the section's units).
struct FeedbackKey {
  const char* key;
  const char* unit;
  const char* description;
  bool gain;  ///< written as {value, std}
};
inline constexpr std::array<FeedbackKey, 20> kFeedbackKeys = {{
    {"kp", "", "proportional gain (controller units: docs/models.md#feedback-gains)", true},
    {"kd", "", "derivative gain on the rate error", true},
    {"ki", "", "integral gain of the speed loop [effort/position]", true},
    {"period", "s", "controller period", false},
    {"delay", "s", "measurement delay compensated", false},
    {"plant_delay", "s", "speed loop: the drive's delay from torque command to measured speed (fitted or given)", false},
    {"loop_delay", "s", "speed loop: the delay designed for, plant_delay + 1.5 periods", false},
    {"max_position_error", "position", "LQR: tolerated position error", false},
    {"max_velocity_error", "position/s", "LQR: tolerated velocity error", false},
    {"max_effort", "effort", "LQR: effort at those errors", false},
    {"conversion", "", "controller units per position unit", false},
    {"notch_hz", "Hz", "notch centre (the fitted resonance)", false},
    {"notch_width_hz", "Hz", "notch -3 dB width", false},
    {"crossover_hz", "Hz", "open-loop gain crossover", false},
    {"phase_margin_deg", "deg", "phase margin", false},
    {"gain_margin_db", "dB", "gain margin", false},
    {"modulus_margin", "", "min |1 + L(jw)|", false},
    {"worst_phase_margin_deg", "deg", "phase margin at the worst point of the 95 % region", false},
    {"worst_gain_margin_db", "dB", "gain margin at the worst point of the 95 % region", false},
    {"worst_modulus_margin", "", "modulus margin at the worst point of the 95 % region", false},
}};

/// The gains' keys, as the table spells them (code names a gain by these,
/// never by a literal of its own).
inline constexpr const char* kGainKp = kFeedbackKeys[0].key;
inline constexpr const char* kGainKd = kFeedbackKeys[1].key;
inline constexpr const char* kGainKi = kFeedbackKeys[2].key;

/// The declaration of `key`, or nullptr.
inline const FeedbackKey* FindFeedbackKey(const std::string& key) {
  for (const auto& k : kFeedbackKeys) {
    if (key == k.key) return &k;
  }
  return nullptr;
}

struct FeedbackValue {
  std::string key;
  double value = 0.0;
  double standard_error = 0.0;
  /// A gain's 95 % interval (sampled over the fit's covariance: it need not
  /// be symmetric about the value); NaN where none was computed.
  double ci95_low = std::numeric_limits<double>::quiet_NaN();
  double ci95_high = std::numeric_limits<double>::quiet_NaN();
  bool HasInterval() const { return ci95_low == ci95_low && ci95_high == ci95_high; }
};

struct FeedbackController {
  std::string loop;    ///< kFeedbackLoops
  std::string preset;  ///< a controller preset's name, or "custom"
  std::string effort_unit;
  std::string position_unit;
  std::vector<FeedbackValue> values;  ///< kFeedbackKeys, in that order
  std::vector<double> numerator;      ///< speed loop: C(s), highest power of s first
  std::vector<double> denominator;
  /// Speed loop: C(z) at `period` (Tustin prewarped at the notch), powers
  /// z^0, z^-1, ... with denominator_z[0] = 1:
  /// u[k] = sum_i numerator_z[i] e[k-i] - sum_{i>0} denominator_z[i] u[k-i].
  std::vector<double> numerator_z;
  std::vector<double> denominator_z;

  const FeedbackValue* Find(const std::string& key) const {
    for (const auto& v : values) {
      if (v.key == key) return &v;
    }
    return nullptr;
  }
  bool empty() const { return loop.empty(); }
};

/// A key's unit in a section: "position", "position/s" and "effort" stand
/// for the section's own units.
inline std::string FeedbackKeyUnit(const FeedbackKey& key, const FeedbackController& f) {
  const std::string unit = key.unit;
  if (unit == "position") return f.position_unit;
  if (unit == "position/s") return f.position_unit + "/s";
  if (unit == "effort") return f.effort_unit;
  return unit;
}

}  // namespace driveid
