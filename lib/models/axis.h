// Rigid single axis (docs/models.md#axis; seed 000 section 5 per actuator,
// friction at constant rates):
//   tau = J q'' + b q' + tau_c sgn(q') + tau_0 + g_c cos q + g_s sin q
//         + tau_c+ [q' > 0] - tau_c- [q' < 0] + b+ max(q', 0) + b- min(q', 0)
//         + tau_s exp(-(q'/v_s)^2) sgn(q'),
//   sgn(0) = 0. The Stribeck term (breakaway tau_c + tau_s) is nonlinear in
//   v_s: only the output-error fit estimates it.
// The direction-dependent terms (coulomb_pos/neg, viscous_pos/neg; tau_c-
// and b- are magnitudes) replace coulomb and viscous when fitted: both at
// once are collinear and refused by the fit; so are an offset and both
// Coulomb directions (offset = tau_c+ [q' > 0] + ... spans the same columns
// where the axis never rests).
// The gravity terms g_c cos q + g_s sin q = A cos(q - phi) (A = hypot(g_c,
// g_s), phi = atan2(g_s, g_c)) hold for a joint whose other joints stand
// still, q in rad; they are 0 unless given or fitted.
// Unit-agnostic: rotary (rad, N m, kg m^2) or linear (m, N, kg) axes; the
// table states rotary units, AxisUnit the linear ones. On a linear axis
// (`axis.linear: true`, --linear) gravity is a constant force — the offset —
// and the cos q / sin q terms do not exist.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "models/parameter_table.h"

namespace driveid {

struct AxisParameters {
  double inertia = 0.0;  ///< J [kg m^2 or kg]
  double viscous = 0.0;  ///< b [N m s/rad or N s/m]
  double coulomb = 0.0;  ///< tau_c [N m or N]
  double offset = 0.0;   ///< tau_0 [N m or N]
  double gravity_cos = 0.0;  ///< g_c [N m]: gravity torque g_c cos q
  double gravity_sin = 0.0;  ///< g_s [N m]: gravity torque g_s sin q
  double coulomb_pos = 0.0;  ///< tau_c+ [N m]: Coulomb friction moving forward (q' > 0)
  double coulomb_neg = 0.0;  ///< tau_c- [N m]: its magnitude moving backward (q' < 0)
  double viscous_pos = 0.0;  ///< b+ [N m s/rad]: viscous friction moving forward
  double viscous_neg = 0.0;  ///< b- [N m s/rad]: viscous friction moving backward
  double stribeck = 0.0;           ///< tau_s [N m]: breakaway excess over Coulomb, fading with speed
  double stribeck_velocity = 0.0;  ///< v_s [rad/s]: speed over which it fades, exp(-(q'/v_s)^2)
};

/// The parameter file's `axis` section: every value optional.
struct AxisSection {
  static constexpr const char* kSectionName = "axis";
  std::optional<double> inertia, viscous, coulomb, offset, gravity_cos, gravity_sin;
  std::optional<double> coulomb_pos, coulomb_neg, viscous_pos, viscous_neg;
  std::optional<double> torque_constant;  ///< k_t [N m/A], for logs of current
  std::optional<double> gear_ratio;       ///< n_g [-], to report d_g = b / n_g^2
  std::optional<double> stribeck, stribeck_velocity;
  /// When the logged torque acts after its stamp [samples]: the IDIM fit's
  /// reading (0 sampled, 0.5 held, else estimated), which validate reuses.
  std::optional<double> torque_delay;
  bool linear = false;  ///< q in m, forces in N (`linear: true`); else rotary
};

/// The axis parameters: key, symbol, unit, bound, fit membership.
inline const ParameterTable<AxisSection, AxisParameters>& AxisParameterTable() {
  static const ParameterTable<AxisSection, AxisParameters> table = {
      {Spec("inertia", "J", "kg m^2", "inertia").Fit("axis").FreeByDefault(),
       &AxisSection::inertia, &AxisParameters::inertia},
      {Spec("viscous", "b", "N m s/rad", "viscous friction").Fit("axis").FreeByDefault(),
       &AxisSection::viscous, &AxisParameters::viscous},
      {Spec("coulomb", "tau_c", "N m", "Coulomb friction").Fit("axis").FreeByDefault(),
       &AxisSection::coulomb, &AxisParameters::coulomb},
      {Spec("offset", "tau_0", "N m", "constant offset").Unbounded().Fit("axis").FreeByDefault(),
       &AxisSection::offset, &AxisParameters::offset},
      {Spec("gravity_cos", "g_c", "N m", "gravity torque amplitude of cos q (q in rad)").Unbounded().Fit("axis"),
       &AxisSection::gravity_cos, &AxisParameters::gravity_cos},
      {Spec("gravity_sin", "g_s", "N m", "gravity torque amplitude of sin q (q in rad)").Unbounded().Fit("axis"),
       &AxisSection::gravity_sin, &AxisParameters::gravity_sin},
      {Spec("coulomb_pos", "tau_c+", "N m", "Coulomb friction moving forward (q' > 0)").Fit("axis"),
       &AxisSection::coulomb_pos, &AxisParameters::coulomb_pos},
      {Spec("coulomb_neg", "tau_c-", "N m", "Coulomb friction moving backward (magnitude, q' < 0)").Fit("axis"),
       &AxisSection::coulomb_neg, &AxisParameters::coulomb_neg},
      {Spec("viscous_pos", "b+", "N m s/rad", "viscous friction moving forward").Fit("axis"),
       &AxisSection::viscous_pos, &AxisParameters::viscous_pos},
      {Spec("viscous_neg", "b-", "N m s/rad", "viscous friction moving backward").Fit("axis"),
       &AxisSection::viscous_neg, &AxisParameters::viscous_neg},
      {Spec("k_t", "k_t", "N m/A", "torque constant for logs of current").Above(0.0),
       &AxisSection::torque_constant, nullptr},
      {Spec("n_g", "n_g", "-", "gear ratio, to report d_g = b / n_g^2").Above(0.0),
       &AxisSection::gear_ratio, nullptr},
      {Spec("torque_delay", "d_u", "samples",
            "when the logged torque acts after its stamp, as the fit read it (0 sampled, 0.5 held; validate reuses "
            "it; docs/models.md#torque-timing)").Unbounded(),
       &AxisSection::torque_delay, nullptr},
      // Nonlinear terms after the settings, so that rows 0 .. kAxisTerms - 1
      // are the linear ones (CalcAxisRegressors).
      {Spec("stribeck", "tau_s", "N m", "Stribeck breakaway excess over Coulomb (output error only)").Fit("axis"),
       &AxisSection::stribeck, &AxisParameters::stribeck},
      {Spec("stribeck_velocity", "v_s", "rad/s", "Stribeck velocity: the excess fades as exp(-(q'/v_s)^2)").Fit("axis"),
       &AxisSection::stribeck_velocity, &AxisParameters::stribeck_velocity},
  };
  return table;
}

/// The unit of an axis parameter (the table's, rotary) on a rotary or a
/// linear axis: kg m^2 -> kg, N m s/rad -> N s/m, N m -> N, rad/s -> m/s,
/// N m/A -> N/A.
inline std::string AxisUnit(const ParameterSpec& spec, bool linear) {
  const std::string unit = spec.unit;
  if (!linear) return unit;
  if (unit == "kg m^2") return "kg";
  if (unit == "N m s/rad") return "N s/m";
  if (unit == "N m") return "N";
  if (unit == "rad/s") return "m/s";
  if (unit == "N m/A") return "N/A";
  return unit;
}

/// The unit of an axis parameter in a log's own units, effort `effort` and
/// position `position` (SysId: "V" and "Meters"): kg m^2 -> V s^2/Meters,
/// N m s/rad -> V s/Meters, N m -> V, rad/s -> Meters/s (the feed-forward
/// gains' units, models/feedforward.h).
inline std::string AxisUnitIn(const ParameterSpec& spec, const std::string& effort, const std::string& position) {
  const std::string unit = spec.unit;
  if (unit == "kg m^2") return effort + " s^2/" + position;
  if (unit == "N m s/rad") return effort + " s/" + position;
  if (unit == "N m") return effort;
  if (unit == "rad/s") return position + "/s";
  return unit;
}

/// The linear model terms: the table's first rows, in table order (the
/// Stribeck pair follows the settings k_t, n_g).
constexpr std::size_t kAxisTerms = 10;
/// Index of each term in CalcAxisRegressors and AxisTermMembers.
enum AxisTermIndex : int {
  kAxisInertia, kAxisViscous, kAxisCoulomb, kAxisOffset, kAxisGravityCos, kAxisGravitySin,
  kAxisCoulombPos, kAxisCoulombNeg, kAxisViscousPos, kAxisViscousNeg
};

/// The parameter a direction-dependent pair replaces ("" for others):
/// coulomb_pos/neg replace coulomb, viscous_pos/neg replace viscous.
inline std::string AxisReplacedBy(const std::string& key) {
  const auto& table = AxisParameterTable();
  if (key == KeyOf(table, &AxisParameters::coulomb_pos) || key == KeyOf(table, &AxisParameters::coulomb_neg)) {
    return KeyOf(table, &AxisParameters::coulomb);
  }
  if (key == KeyOf(table, &AxisParameters::viscous_pos) || key == KeyOf(table, &AxisParameters::viscous_neg)) {
    return KeyOf(table, &AxisParameters::viscous);
  }
  return "";
}

/// Terms that are 0 unless the parameter file gives them: all but J, b,
/// tau_c, tau_0, which the classic axis needs; also b or tau_c where the
/// file gives a direction-dependent term in its place, and tau_0 where it
/// gives both Coulomb directions (which span it).
inline std::vector<std::string> AxisTermsZeroUnlessGiven(const AxisSection& given = {}) {
  std::vector<std::string> keys;
  const auto& table = AxisParameterTable();
  for (const auto& row : table) {
    if (row.in_model == nullptr) continue;
    const std::string key = row.spec.key;
    if (!row.spec.default_free) keys.push_back(key);
    if (given.*(row.in_section) && !AxisReplacedBy(key).empty()) keys.push_back(AxisReplacedBy(key));
  }
  if (given.coulomb_pos && given.coulomb_neg) keys.push_back(KeyOf(table, &AxisParameters::offset));
  return keys;
}

/// The regressor of each term at a position, rate, acceleration and
/// direction of motion (+1 forward, -1 backward, 0 at rest), in table order:
/// tau = sum_j p_j phi_j. The direction is sgn(rate) except in a simulation
/// at the instant the rate crosses 0 (sim/axis_simulator.h).
inline std::array<double, kAxisTerms> CalcAxisRegressors(double position, double rate, double acceleration,
                                                         int direction) {
  const double forward = direction > 0 ? 1.0 : 0.0, backward = direction < 0 ? 1.0 : 0.0;
  return {acceleration, rate, forward - backward, 1.0, std::cos(position), std::sin(position),
          forward, -backward, forward * rate, backward * rate};
}

/// The regressors with the direction sgn(rate) (sgn(0) = 0: at rest neither).
inline std::array<double, kAxisTerms> CalcAxisRegressors(double position, double rate, double acceleration) {
  return CalcAxisRegressors(position, rate, acceleration, (rate > 0.0) - (rate < 0.0));
}

/// The model members in table order (index j of the regressors).
inline const std::array<double AxisParameters::*, kAxisTerms>& AxisTermMembers() {
  static const std::array<double AxisParameters::*, kAxisTerms> members = [] {
    std::array<double AxisParameters::*, kAxisTerms> out{};
    for (std::size_t j = 0; j < kAxisTerms; ++j) out[j] = AxisParameterTable()[j].in_model;
    return out;
  }();
  return members;
}

/// Term indices after the linear ones: the Stribeck pair (nonlinear).
constexpr int kAxisStribeck = static_cast<int>(kAxisTerms), kAxisStribeckVelocity = kAxisStribeck + 1;
constexpr int kAxisAllTerms = kAxisStribeckVelocity + 1;

/// The table row of term index `term` (0 .. kAxisAllTerms - 1).
inline const ParameterRow<AxisSection, AxisParameters>& AxisTermRow(int term) {
  const auto& table = AxisParameterTable();
  if (term < static_cast<int>(kAxisTerms)) return table[static_cast<std::size_t>(term)];
  const double AxisParameters::*member =
      term == kAxisStribeck ? &AxisParameters::stribeck : &AxisParameters::stribeck_velocity;
  for (const auto& row : table) {
    if (row.in_model == member) return row;
  }
  throw std::logic_error("AxisTermRow: no such term");
}

/// The Stribeck excess tau_s exp(-(v/v_s)^2) in the direction of motion
/// (0 at rest and where v_s <= 0).
inline double CalcStribeckForce(const AxisParameters& p, double rate, int direction) {
  if (p.stribeck == 0.0 || !(p.stribeck_velocity > 0.0) || direction == 0) return 0.0;
  const double x = rate / p.stribeck_velocity;
  return direction * p.stribeck * std::exp(-x * x);
}

/// Force/torque of the axis at a position, rate and acceleration.
inline double CalcAxisForce(const AxisParameters& p, double position, double rate, double acceleration) {
  const std::array<double, kAxisTerms> phi = CalcAxisRegressors(position, rate, acceleration);
  const auto& members = AxisTermMembers();
  double tau = 0.0;
  for (std::size_t j = 0; j < kAxisTerms; ++j) tau += p.*members[j] * phi[j];
  return tau + CalcStribeckForce(p, rate, (rate > 0.0) - (rate < 0.0));
}

}  // namespace driveid
