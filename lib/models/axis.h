// Rigid single axis (docs/models.md#axis; seed 000 section 5 per actuator,
// friction at constant rates):
//   tau = J q'' + b q' + tau_c sgn(q') + tau_0 + g_c cos q + g_s sin q,
//   sgn(0) = 0.
// The gravity terms g_c cos q + g_s sin q = A cos(q - phi) (A = hypot(g_c,
// g_s), phi = atan2(g_s, g_c)) hold for a joint whose other joints stand
// still, q in rad; they are 0 unless given or fitted.
// Unit-agnostic: rotary (rad, N m, kg m^2) or linear (m, N, kg) axes.
#pragma once

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
};

/// The parameter file's `axis` section: every value optional.
struct AxisSection {
  static constexpr const char* kSectionName = "axis";
  std::optional<double> inertia, viscous, coulomb, offset, gravity_cos, gravity_sin;
  std::optional<double> torque_constant;  ///< k_t [N m/A], for logs of current
  std::optional<double> gear_ratio;       ///< n_g [-], to report d_g = b / n_g^2
};

/// The axis parameters: key, symbol, unit, bound, fit membership.
inline const ParameterTable<AxisSection, AxisParameters>& AxisParameterTable() {
  static const ParameterTable<AxisSection, AxisParameters> table = {
      {{"inertia", "J", "kg m^2 (linear axis: kg)", "inertia", 0.0, false, false, "axis", true, 0.0},
       &AxisSection::inertia, &AxisParameters::inertia},
      {{"viscous", "b", "N m s/rad (linear: N s/m)", "viscous friction", 0.0, false, false, "axis", true, 0.0},
       &AxisSection::viscous, &AxisParameters::viscous},
      {{"coulomb", "tau_c", "N m (linear: N)", "Coulomb friction", 0.0, false, false, "axis", true, 0.0},
       &AxisSection::coulomb, &AxisParameters::coulomb},
      {{"offset", "tau_0", "N m (linear: N)", "constant offset", kUnbounded, false, false, "axis", true, 0.0},
       &AxisSection::offset, &AxisParameters::offset},
      {{"gravity_cos", "g_c", "N m", "gravity torque amplitude of cos q (q in rad)", kUnbounded, false, false, "axis",
        false, 0.0},
       &AxisSection::gravity_cos, &AxisParameters::gravity_cos},
      {{"gravity_sin", "g_s", "N m", "gravity torque amplitude of sin q (q in rad)", kUnbounded, false, false, "axis",
        false, 0.0},
       &AxisSection::gravity_sin, &AxisParameters::gravity_sin},
      {{"k_t", "k_t", "N m/A", "torque constant for logs of current", 0.0, true, false, "", false, 0.0},
       &AxisSection::torque_constant, nullptr},
      {{"n_g", "n_g", "-", "gear ratio, to report d_g = b / n_g^2", 0.0, true, false, "", false, 0.0},
       &AxisSection::gear_ratio, nullptr},
  };
  return table;
}

/// Terms that are 0 unless the parameter file gives them.
inline std::vector<std::string> AxisTermsZeroUnlessGiven() {
  return {KeyOf(AxisParameterTable(), &AxisParameters::gravity_cos),
          KeyOf(AxisParameterTable(), &AxisParameters::gravity_sin)};
}

/// Force/torque of the axis at a position, rate and acceleration (sgn(0) = 0).
inline double CalcAxisForce(const AxisParameters& p, double position, double rate, double acceleration) {
  const double sign = static_cast<double>((rate > 0.0) - (rate < 0.0));
  return p.inertia * acceleration + p.viscous * rate + p.coulomb * sign + p.offset +
         p.gravity_cos * std::cos(position) + p.gravity_sin * std::sin(position);
}

}  // namespace driveid
