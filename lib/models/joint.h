// Elastic joint, two masses (docs/models.md#elastic-joint): a motor and a
// link coupled by a spring-damper through a gear of known ratio n. Referred
// to the link side, theta_m = q_motor / n and tau_m = n tau:
//   J_m theta_m'' = tau_m - k (theta_m - theta_l) - d (theta_m' - theta_l')
//                   - b_m theta_m' - c_m sgn(theta_m') - tau_0
//   J_l theta_l'' = k (theta_m - theta_l) + d (theta_m' - theta_l')
//                   - b_l theta_l' - c_l sgn(theta_l') - g_c cos theta_l - g_s sin theta_l
// Units: kg m^2, N m/rad, N m s/rad, N m, rad (link side).
// The identification (fit/joint/joint_fit.h) uses the motor equation and the sum
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

/// The joint section's rows: the registered terms' (models/joint_term.h) in
/// their order, then the settings n and k_t.
const ParameterTable<JointSection, JointParameters>& JointParameterTable();

/// The model parameters (JointParameters' members) and those of them linear
/// in the motion (J_m, J_l, k, d, b_m, b_l: the frequency response's).
constexpr std::size_t kJointTerms = 12;
constexpr std::size_t kJointLinearTerms = 6;

/// Regressor rows of the motor, the total and the shaft-torque equation at
/// one sample (table order; link-side angles and rates):
/// motor = [theta_m'', 0, D, D', theta_m', sgn theta_m', 0, 0, 1, 0, 0, 0],
/// total = [theta_m'', theta_l'', 0, 0, theta_m', sgn theta_m', theta_l', sgn theta_l', 1, cos, sin, 0],
/// link  = [0, 0, D, D', 0, 0, 0, 0, 0, 0, 0, 1].
struct JointRegressors {
  std::array<double, kJointTerms> motor, total, link;
};
/// From the registered terms' columns (models/joint_terms.cc).
JointRegressors CalcJointRegressors(double motor_angle, double motor_rate, double motor_acceleration,
                                    double link_angle, double link_rate, double link_acceleration);

/// Which derivative of an angle a frequency response has as its output.
enum class ResponseQuantity { kPosition = 0, kRate = 1, kAcceleration = 2 };

/// Frequency response of the joint from the logged motor torque tau (= tau_m / n)
/// at s = j omega [rad/s], in log units (q_motor = n theta_m, q_link = theta_l),
/// gravity left out (linear about rest). From the linear terms' matrices
/// (models/joint_term.h), Z(s) = M s^2 + D s + K and Delta = det Z:
///   q_motor / tau = n^2 Z_ll / Delta,   q_link / tau = -n Z_lm / Delta,
/// which for the registered terms is, with A_m = J_m s^2 + (b_m + d) s + k,
/// A_l = J_l s^2 + (b_l + d) s + k and K = d s + k, Delta = A_m A_l - K^2:
///   q_motor / tau = n^2 A_l / Delta,   q_link / tau = n K / Delta,
/// times s (rate) or s^2 (acceleration). Coulomb friction and the offset do
/// not enter (a describing function would make the response depend on the
/// amplitude). Undamped, the motor response has its anti-resonance at
/// sqrt(k / J_l) and both share the resonance sqrt(k (1/J_m + 1/J_l)).
struct JointResponse {
  std::complex<double> motor, link;
  /// d ln(response) / d parameter for the linear terms, in the order of
  /// JointLinearParameters(): motor_inertia, link_inertia, stiffness,
  /// damping, motor_viscous, link_viscous.
  std::array<std::complex<double>, kJointLinearTerms> motor_log_gradient, link_log_gradient;
};
JointResponse CalcJointResponse(const JointParameters& p, double gear_ratio, double omega, ResponseQuantity quantity);

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
