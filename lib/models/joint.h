// Elastic joint, two masses (docs/models.md#elastic-joint): a motor and a
// link coupled by a spring-damper through a gear of known ratio n. Referred
// to the link side, theta_m = q_motor / n and tau_m = n tau:
//   J_m theta_m'' = tau_m - k (theta_m - theta_l) - d (theta_m' - theta_l')
//                   - b_m theta_m' - c_m sgn(theta_m') - tau_0
//   J_l theta_l'' = k (theta_m - theta_l) + d (theta_m' - theta_l')
//                   - b_l theta_l' - c_l sgn(theta_l') - g_c cos theta_l - g_s sin theta_l
// Units: kg m^2, N m/rad, N m s/rad, N m, rad (link side).
// The identification (fit/joint_fit.h) uses the motor equation and the sum
// of both (the spring cancels), each with the measured tau_m as its target:
//   motor: tau_m = J_m theta_m'' + k D + d D' + b_m theta_m' + c_m sgn theta_m' + tau_0
//   total: tau_m = J_m theta_m'' + J_l theta_l'' + b_m theta_m' + c_m sgn theta_m'
//                  + b_l theta_l' + c_l sgn theta_l' + tau_0 + g_c cos theta_l + g_s sin theta_l
// with D = theta_m - theta_l. Both are linear in the parameters. A torque
// sensor in the elastic element (strain gauges, a bench's transducer) adds
//   link:  tau_link = k D + d D' + tau_l0
// with tau_l0 the sensor's bias plus the unknown initial twist of angles
// integrated from speeds (k times it).
#pragma once

#include <array>
#include <cmath>
#include <complex>
#include <optional>
#include <vector>
#include <string>

#include "models/parameter_table.h"

namespace driveid {

struct JointParameters {
  double motor_inertia = 0.0;  ///< J_m [kg m^2], link side (n^2 x the rotor's)
  double link_inertia = 0.0;   ///< J_l [kg m^2]
  double stiffness = 0.0;      ///< k [N m/rad]
  double damping = 0.0;        ///< d [N m s/rad], of the spring
  double motor_viscous = 0.0;  ///< b_m [N m s/rad]
  double motor_coulomb = 0.0;  ///< c_m [N m]
  double link_viscous = 0.0;   ///< b_l [N m s/rad]
  double link_coulomb = 0.0;   ///< c_l [N m]
  double offset = 0.0;         ///< tau_0 [N m], on the motor side
  double gravity_cos = 0.0;    ///< g_c [N m]
  double gravity_sin = 0.0;    ///< g_s [N m]
  double link_torque_offset = 0.0;  ///< tau_l0 [N m], of the shaft-torque channel
};

struct JointSection {
  static constexpr const char* kSectionName = "joint";
  std::optional<double> motor_inertia, link_inertia, stiffness, damping, motor_viscous, motor_coulomb, link_viscous,
      link_coulomb, offset, gravity_cos, gravity_sin, link_torque_offset;
  std::optional<double> gear_ratio;       ///< n [-], q_motor = n theta_m (required)
  std::optional<double> torque_constant;  ///< k_t [N m/A] for logs of current i
};

inline const ParameterTable<JointSection, JointParameters>& JointParameterTable() {
  using S = JointSection;
  using P = JointParameters;
  static const ParameterTable<S, P> table = {
      {Spec("motor_inertia", "J_m", "kg m^2", "motor inertia, link side").Fit("joint").FreeByDefault(),
       &S::motor_inertia, &P::motor_inertia},
      {Spec("link_inertia", "J_l", "kg m^2", "link inertia").Fit("joint").FreeByDefault(),
       &S::link_inertia, &P::link_inertia},
      {Spec("stiffness", "k", "N m/rad", "joint stiffness").Fit("joint").FreeByDefault(), &S::stiffness,
       &P::stiffness},
      {Spec("damping", "d", "N m s/rad", "joint damping (of the spring)").Fit("joint").FreeByDefault(),
       &S::damping, &P::damping},
      {Spec("motor_viscous", "b_m", "N m s/rad", "motor-side viscous friction").Fit("joint").FreeByDefault(),
       &S::motor_viscous, &P::motor_viscous},
      {Spec("motor_coulomb", "c_m", "N m", "motor-side Coulomb friction").Fit("joint").FreeByDefault(),
       &S::motor_coulomb, &P::motor_coulomb},
      {Spec("link_viscous", "b_l", "N m s/rad", "link-side viscous friction").Fit("joint").FreeByDefault(),
       &S::link_viscous, &P::link_viscous},
      {Spec("link_coulomb", "c_l", "N m", "link-side Coulomb friction").Fit("joint").FreeByDefault(),
       &S::link_coulomb, &P::link_coulomb},
      {Spec("offset", "tau_0", "N m", "constant torque offset (motor side)").Unbounded().Fit("joint").FreeByDefault(),
       &S::offset, &P::offset},
      {Spec("gravity_cos", "g_c", "N m", "gravity torque amplitude of cos q_link").Unbounded().Fit("joint"),
       &S::gravity_cos, &P::gravity_cos},
      {Spec("gravity_sin", "g_s", "N m", "gravity torque amplitude of sin q_link").Unbounded().Fit("joint"),
       &S::gravity_sin, &P::gravity_sin},
      {Spec("link_torque_offset", "tau_l0", "N m",
            "offset of a logged shaft torque tau_link (sensor bias + k x initial twist)")
           .Unbounded()
           .Fit("joint"),
       &S::link_torque_offset, &P::link_torque_offset},
      {Spec("gear_ratio", "n", "-", "gear ratio, q_motor = n theta_m").Above(0.0).Required(),
       &S::gear_ratio, nullptr},
      {Spec("k_t", "k_t", "N m/A", "torque constant for logs of current").Above(0.0),
       &S::torque_constant, nullptr},
  };
  return table;
}

constexpr std::size_t kJointTerms = 12;

/// Regressor rows of the motor, the total and the shaft-torque equation at
/// one sample (table order; link-side angles and rates):
/// motor = [theta_m'', 0, D, D', theta_m', sgn theta_m', 0, 0, 1, 0, 0, 0],
/// total = [theta_m'', theta_l'', 0, 0, theta_m', sgn theta_m', theta_l', sgn theta_l', 1, cos, sin, 0],
/// link  = [0, 0, D, D', 0, 0, 0, 0, 0, 0, 0, 1].
struct JointRegressors {
  std::array<double, kJointTerms> motor, total, link;
};
inline JointRegressors CalcJointRegressors(double motor_angle, double motor_rate, double motor_acceleration,
                                           double link_angle, double link_rate, double link_acceleration) {
  const auto sgn = [](double x) { return static_cast<double>((x > 0.0) - (x < 0.0)); };
  const double deflection = motor_angle - link_angle, deflection_rate = motor_rate - link_rate;
  return {{motor_acceleration, 0.0, deflection, deflection_rate, motor_rate, sgn(motor_rate), 0.0, 0.0, 1.0, 0.0, 0.0,
           0.0},
          {motor_acceleration, link_acceleration, 0.0, 0.0, motor_rate, sgn(motor_rate), link_rate, sgn(link_rate), 1.0,
           std::cos(link_angle), std::sin(link_angle), 0.0},
          {0.0, 0.0, deflection, deflection_rate, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0}};
}

/// Which derivative of an angle a frequency response has as its output.
enum class ResponseQuantity { kPosition = 0, kRate = 1, kAcceleration = 2 };

/// Frequency response of the joint from the logged motor torque tau (= tau_m / n)
/// at s = j omega [rad/s], in log units (q_motor = n theta_m, q_link = theta_l),
/// gravity left out (linear about rest). With A_m = J_m s^2 + (b_m + d) s + k,
/// A_l = J_l s^2 + (b_l + d) s + k, K = d s + k and Delta = A_m A_l - K^2:
///   q_motor / tau = n^2 A_l / Delta,   q_link / tau = n K / Delta,
/// times s (rate) or s^2 (acceleration). Coulomb friction and the offset do
/// not enter (a describing function would make the response depend on the
/// amplitude). Undamped, the motor response has its anti-resonance at
/// sqrt(k / J_l) and both share the resonance sqrt(k (1/J_m + 1/J_l)).
struct JointResponse {
  std::complex<double> motor, link;
  /// d ln(response) / d parameter for the dynamic terms, in the order
  /// motor_inertia, link_inertia, stiffness, damping, motor_viscous, link_viscous.
  std::array<std::complex<double>, 6> motor_log_gradient, link_log_gradient;
};
inline JointResponse CalcJointResponse(const JointParameters& p, double gear_ratio, double omega,
                                       ResponseQuantity quantity) {
  using C = std::complex<double>;
  const C s(0.0, omega);
  const C spring = p.damping * s + p.stiffness;
  const C a_m = p.motor_inertia * s * s + p.motor_viscous * s + spring;
  const C a_l = p.link_inertia * s * s + p.link_viscous * s + spring;
  const C delta = a_m * a_l - spring * spring;
  const C derivative = std::pow(s, static_cast<int>(quantity));
  JointResponse out;
  out.motor = gear_ratio * gear_ratio * a_l / delta * derivative;
  out.link = gear_ratio * spring / delta * derivative;
  // Partials of (A_m, A_l, K) per parameter.
  const std::array<std::array<C, 3>, 6> partials = {{{s * s, 0.0, 0.0},
                                                     {0.0, s * s, 0.0},
                                                     {1.0, 1.0, 1.0},
                                                     {s, s, s},
                                                     {s, 0.0, 0.0},
                                                     {0.0, s, 0.0}}};
  for (std::size_t i = 0; i < partials.size(); ++i) {
    const auto& [da_m, da_l, dk] = partials[i];
    const C d_delta = da_m * a_l + a_m * da_l - 2.0 * spring * dk;
    out.motor_log_gradient[i] = da_l / a_l - d_delta / delta;
    out.link_log_gradient[i] = dk / spring - d_delta / delta;
  }
  return out;
}

/// The same response as a sampled system sees it: the torque held between
/// samples at `rate` [Hz] (zero-order hold) and the output sampled, exactly:
/// with x = (theta_m, theta_m', theta_l, theta_l') and x' = A x + B tau,
/// [Phi Gamma; 0 1] = exp([A B; 0 0] T) and H(z) = C (z I - Phi)^-1 Gamma + D
/// at z = exp(j omega T), for omega below the Nyquist frequency; the hold's
/// delay and aliasing are part of it. Gradients are not filled.
class SampledJointResponse {
 public:
  SampledJointResponse(const JointParameters& p, double gear_ratio, double rate);
  std::complex<double> Motor(double omega, ResponseQuantity quantity) const;
  std::complex<double> Link(double omega, ResponseQuantity quantity) const;

 private:
  std::complex<double> Evaluate(double omega, const std::array<double, 4>& c, double d) const;
  std::array<std::array<double, 4>, 4> a_{}, phi_{};
  std::array<double, 4> b_{}, gamma_{};
  double gear_ratio_, period_;
};

/// Undamped resonance sqrt(k (1/J_m + 1/J_l)) and motor-side anti-resonance
/// sqrt(k / J_l) [rad/s].
inline double JointResonance(const JointParameters& p) {
  return std::sqrt(p.stiffness * (1.0 / p.motor_inertia + 1.0 / p.link_inertia));
}
inline double JointAntiresonance(const JointParameters& p) { return std::sqrt(p.stiffness / p.link_inertia); }

/// The frequency-response fit's and design's default free set: the keys of
/// J_m, J_l, k, d and b_m (the terms a two-mass response determines best).
std::vector<std::string> TwoMassDefaultFree();

}  // namespace driveid
