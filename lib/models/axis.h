// Rigid single axis (SPEC 5.2; seed 000 section 5 per actuator, friction at
// constant rates): tau = J q'' + b q' + tau_c sgn(q') + tau_0.
// Unit-agnostic: rotary (rad, N m, kg m^2) or linear (m, N, kg) axes.
#pragma once

namespace driveid {

struct AxisParameters {
  double inertia = 0.0;  ///< J [kg m^2 or kg]
  double viscous = 0.0;  ///< b [N m s/rad or N s/m]
  double coulomb = 0.0;  ///< tau_c [N m or N]
  double offset = 0.0;   ///< tau_0 [N m or N]
};

/// Force/torque of the axis at a rate and acceleration (sgn(0) = 0).
inline double CalcAxisForce(const AxisParameters& p, double rate, double acceleration) {
  const double sign = static_cast<double>((rate > 0.0) - (rate < 0.0));
  return p.inertia * acceleration + p.viscous * rate + p.coulomb * sign + p.offset;
}

}  // namespace driveid
