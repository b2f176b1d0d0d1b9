// Rigid single axis (docs/models.md#axis; seed 000 section 5 per actuator,
// friction at constant rates):
//   tau = J q'' + sum over the model's terms of their forces F_t(q, q', m),
// m = sgn(q') the direction of motion (sgn(0) = 0). Each term is an object
// (models/axis_term.h) in a file of its own under models/axis_terms/, and
// models/axis_terms.cc registers them: the linear ones (F = sum_i p_i
// phi_i, which inverse dynamics fits: inertia J q'', viscous b q', Coulomb
// tau_c sgn(q'), offset tau_0, gravity g_c cos q + g_s sin q, Coulomb per
// direction tau_c+ [q' > 0] - tau_c- [q' < 0], viscous per direction
// b+ max(q', 0) + b- min(q', 0)), then the nonlinear ones, which only the
// output-error fit estimates. The parameter table is theirs, in that order.
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

/// Slots for the parameters of terms registered without a member of their
/// own below (models/axis_terms.cc assigns them in registration order).
inline constexpr std::size_t kAxisExtraSlots = 8;

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
  /// The other terms' parameters, by slot (their rows say which).
  std::array<double, kAxisExtraSlots> extra{};
};

/// The parameter file's `axis` section: every value optional.
struct AxisSection {
  static constexpr const char* kSectionName = "axis";
  std::optional<double> inertia, viscous, coulomb, offset, gravity_cos, gravity_sin;
  std::optional<double> coulomb_pos, coulomb_neg, viscous_pos, viscous_neg;
  std::optional<double> torque_constant;  ///< k_t [N m/A], for logs of current
  std::optional<double> gear_ratio;       ///< n_g [-], to report d_g = b / n_g^2
  /// When the logged torque acts after its stamp [samples]: the IDIM fit's
  /// reading (0 sampled, 0.5 held, else estimated), which validate reuses.
  std::optional<double> torque_delay;
  /// The other terms' parameters, by slot (as AxisParameters::extra).
  std::array<std::optional<double>, kAxisExtraSlots> extra;
  bool linear = false;  ///< q in m, forces in N (`linear: true`); else rotary
};

using AxisRow = ParameterRow<AxisSection, AxisParameters>;
using AxisTable = ParameterTable<AxisSection, AxisParameters>;

/// The axis parameters: key, symbol, unit, bound, fit membership — the
/// registered terms' rows (the linear terms', then the settings k_t, n_g
/// and torque_delay, then the nonlinear terms'); models/axis_terms.cc.
const AxisTable& AxisParameterTable();
/// The key of the axis parameter in `member` ("coulomb"): code names a
/// parameter by its member, not by a restated string.
inline std::string AxisKey(double AxisParameters::*member) { return KeyOf(AxisParameterTable(), member); }

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

/// The model parameters (the table's rows but the settings) by index j,
/// in table order: the linear terms' first (j < AxisLinearCount(): the
/// regressors' order), then the nonlinear terms'.
std::size_t AxisLinearCount();
std::size_t AxisParameterCount();
/// The table row of parameter j.
const AxisRow& AxisTermRow(std::size_t j);
/// The index of the parameter stored in `member`.
std::size_t AxisIndex(double AxisParameters::*member);
/// The index of the parameter named `key`, or AxisParameterCount().
std::size_t AxisIndexOf(const std::string& key);

/// Fixed-size storage for per-parameter values (regressors, parameter vectors).
inline constexpr std::size_t kMaxAxisParameters = 32;
using AxisValues = std::array<double, kMaxAxisParameters>;

/// Every parameter's value in index order.
AxisValues AxisValuesOf(const AxisParameters& p);

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
    if (!row.is_model()) continue;
    const std::string key = row.spec.key;
    if (!row.spec.default_free) keys.push_back(key);
    if (SectionValue(row, given) && !AxisReplacedBy(key).empty()) keys.push_back(AxisReplacedBy(key));
  }
  if (given.coulomb_pos && given.coulomb_neg) keys.push_back(KeyOf(table, &AxisParameters::offset));
  return keys;
}

/// The regressor of each linear parameter at a position, rate, acceleration
/// and direction of motion (+1 forward, -1 backward, 0 at rest), in index
/// order (the first AxisLinearCount() entries): the linear terms' force is
/// sum_j p_j phi_j. The direction is sgn(rate) except in a simulation at the
/// instant the rate crosses 0 (sim/axis_simulator.h).
AxisValues CalcAxisRegressors(double position, double rate, double acceleration, int direction);

/// The regressors with the direction sgn(rate) (sgn(0) = 0: at rest neither).
inline AxisValues CalcAxisRegressors(double position, double rate, double acceleration) {
  return CalcAxisRegressors(position, rate, acceleration, (rate > 0.0) - (rate < 0.0));
}

/// Force/torque of the axis at a position, rate and acceleration (every term).
double CalcAxisForce(const AxisParameters& p, double position, double rate, double acceleration);

}  // namespace driveid
