// Feed-forward gains of a rigid axis (docs/models.md#feed-forward), the
// form WPILib SysId and most motion controllers load:
//   u = Ks sgn(v) + Kv v + Ka a + Kg cos(q - Kg_angle) + offset
// (an elevator's constant Kg is the offset)
// in the log's units: u is the logged effort (V for SysId logs, N m or N
// otherwise), q, v, a the position, rate and acceleration in the log's
// position unit. From the axis model (models/axis.h):
//   Ks = tau_c, Kv = b, Ka = J; with direction-dependent friction Ks and Kv
//   per direction: Ks_forward = tau_c + tau_c+, Ks_backward = tau_c + tau_c-,
//   Kv_forward = b + b+, Kv_backward = b + b-;
//   gravity g_c cos q + g_s sin q = Kg cos(q - Kg_angle) with
//   Kg = hypot(g_c, g_s), Kg_angle = atan2(g_s, g_c) [rad]; offset = tau_0
//   (an elevator's Kg, or a bias if the axis is level: the data cannot tell).
// Each gain carries the standard error propagated from the fit's
// covariance (first order, docs/models.md#feed-forward).
//
// The C-drive's friction compensation, seed 001 eq. (31) (law "cdrive",
// docs/models.md#c-drive), per motor I with the other J:
//   tau_I = beta w_I + delta RL{sgn DZ(w_I)} + gamma_half (w_I - w_J) + eta RL{sgn DZ(w_I - w_J)}
// with gamma_half = gamma / 2, the dead zone DZ and rate limit RL of the
// controller settings (cdrive.control).
#pragma once

#include <array>
#include <string>
#include <vector>

namespace driveid {

/// True for a position unit of length ("m", SysId's "Meters", "Feet",
/// "Inches"): the mechanism is linear (models/axis.h).
inline bool IsLengthUnit(const std::string& unit) {
  for (const char* length : {"m", "mm", "Meters", "Meter", "meters", "Feet", "feet", "ft", "Inches", "inches", "in"}) {
    if (unit == length) return true;
  }
  return false;
}

/// Why `unit` cannot name a unit, or "" when it can: at most 64 bytes of
/// letters, digits, blanks and `/ ^ * . _ ( ) % + -`, without "--", "/*"
/// or "*/". A unit goes into comments and identifiers of every export
/// target (XML, C, C++, Java, JSON): nothing there may close a comment or
/// start an escape (Java decodes \u everywhere).
inline std::string UnitTextProblem(const std::string& unit) {
  if (unit.size() > 64) return "longer than 64 bytes";
  for (char c : unit) {
    const bool letter = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    if (!letter && std::string(" /^*._()%+-").find(c) == std::string::npos) {
      const auto byte = static_cast<unsigned char>(c);
      return byte >= 0x20 && byte < 0x7f ? std::string("the character '") + c + "'" : "a byte that is not printable ASCII";
    }
  }
  for (const char* sequence : {"--", "/*", "*/"}) {
    if (unit.find(sequence) != std::string::npos) return std::string("\"") + sequence + "\"";
  }
  return "";
}

/// True for a position unit of angle ("rad", SysId's "Radians",
/// "Rotations", "Degrees"): the mechanism turns.
inline bool IsAngleUnit(const std::string& unit) {
  for (const char* angle : {"rad", "Radians", "radians", "Radian", "rot", "Rotations", "rotations", "Rotation", "rev",
                            "turns", "deg", "Degrees", "degrees", "Degree"}) {
    if (unit == angle) return true;
  }
  return false;
}

/// The gain keys a feed-forward section may hold, in the order written.
/// Axis: Ks ... offset; C-drive eq. (31) (law "cdrive"): beta, gamma_half,
/// delta, eta, dead_zone, rate_limit.
inline constexpr std::array<const char*, 16> kFeedforwardKeys = {
    "Ks",   "Ks_forward", "Ks_backward", "Kv",    "Kv_forward", "Kv_backward", "Ka",        "Kg",
    "Kg_angle", "offset", "beta",        "gamma_half", "delta", "eta",         "dead_zone", "rate_limit"};

/// The compensation laws a feed-forward section holds.
inline constexpr const char* kAxisFeedforwardLaw = "axis";
inline constexpr const char* kCDriveCompensationLaw = "cdrive";

/// The unit of a gain: Ks, Kg, offset in the effort unit, Kv per rate,
/// Ka per acceleration, Kg_angle in rad.
inline std::string FeedforwardUnit(const std::string& key, const std::string& effort, const std::string& position) {
  if (key.rfind("Kv", 0) == 0 || key == "beta" || key == "gamma_half") return effort + " s/" + position;
  if (key == "dead_zone") return position + "/s";
  if (key == "rate_limit") return "1/s";
  if (key == "Ka") return effort + " s^2/" + position;
  if (key == "Kg_angle") return "rad";
  return effort;
}

struct FeedforwardGain {
  std::string key;           ///< Ks, Ks_forward, Ks_backward, Kv..., Ka, Kg, Kg_angle, offset
  double value = 0.0;
  double standard_error = 0.0;  ///< 0 where every parameter it uses was held fixed
  std::string unit;          ///< in the log's units, e.g. "V s/Meters"
};

/// The feed-forward section of a parameter file.
struct Feedforward {
  std::string law = kAxisFeedforwardLaw;  ///< "axis" or "cdrive" (eq. 31)
  std::string effort_unit;    ///< unit of u: "V", "N m", "N"
  std::string position_unit;  ///< unit of q: "rad", "m", SysId's "Meters", ...
  std::vector<FeedforwardGain> gains;
  /// SysId's analysis type of the logs it was fitted from ("simple",
  /// "elevator", "arm"), "" when they declared none: which WPILib class the
  /// gains belong in (a drive's offset is no elevator's kG).
  std::string mechanism;
};

}  // namespace driveid
