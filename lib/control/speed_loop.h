// A PI speed loop with a notch for an elastic joint (docs/models.md#speed-loop):
// the motor-shaft speed fed back, the plant the two-mass model from the logged
// torque to the motor speed in log units (models/joint.h CalcJointResponse,
// rate output), P(s) = n^2 s A_l(s) / Delta(s), whose Delta holds a factor s:
//   P(s) = n^2 (J_l s^2 + (d + b_l) s + k) / (J_m J_l s^3 + (J_m (d + b_l) + J_l (d + b_m)) s^2
//          + (k (J_m + J_l) + (d + b_m)(d + b_l) - d^2) s + k (b_m + b_l)),
// the controller
//   C(s) = kp (1 + w_i / s) (s^2 + 2 z_z w_n s + w_n^2) / (s^2 + 2 z_p w_n s + w_n^2)
// with the notch at the resonance w_n, its -3 dB width 2 z_p w_n and its
// depth z_z / z_p, and the loop's delay e^(-s tau), tau = tau_p + 1.5 T:
// the drive's own delay tau_p from the torque command to the measured speed
// (measured or fitted) plus the controller's (the computation's period and
// the zero-order hold's half period).
// Margins are read on the exact delay's frequency response. Closed-loop
// stability is judged on the loop as a drive runs it: the plant sampled
// exactly with the zero-order hold and its delay (whole periods and a
// fraction, Astrom & Wittenmark's modified z-transform), the controller
// C(z) by Tustin's rule prewarped at the notch, its torque applied one
// period late; stable when every closed-loop pole lies inside |z| = 1.
#pragma once

#include <complex>
#include <functional>
#include <string>
#include <vector>

#include "models/joint.h"

namespace driveid {

struct PiNotch {
  double kp = 0.0;              ///< [log torque / (log position unit/s)]
  double integral_corner = 0.0; ///< w_i [rad/s]: ki = kp w_i
  double notch_hz = 0.0;
  double notch_width_hz = 0.0;  ///< -3 dB width
  double notch_depth_db = 20.0;
  /// C(s), highest power first: numerator of degree 3, denominator s (s^2 + ...).
  std::vector<double> Numerator() const;
  std::vector<double> Denominator() const;
  std::complex<double> Evaluate(double omega) const;
  /// C(z) at `period` by Tustin's rule prewarped at the notch,
  /// s = w_n / tan(w_n T / 2) (1 - z^-1) / (1 + z^-1): coefficients of
  /// z^0, z^-1, z^-2, z^-3, the denominator's first 1, so that
  /// u[k] = sum_i b_i e[k-i] - sum_{i>0} a_i u[k-i].
  void Discrete(double period, std::vector<double>& numerator, std::vector<double>& denominator) const;
};

struct LoopMargins {
  bool stable = false;
  double crossover_hz = 0.0;      ///< first gain crossover
  double phase_margin_deg = 0.0;  ///< smallest over all gain crossovers
  double gain_margin_db = 0.0;    ///< smallest over all phase crossovers below Nyquist (inf: none)
  double modulus_margin = 0.0;    ///< min |1 + L(jw)| below Nyquist
};

struct SpeedLoopPlant {
  JointParameters joint;
  double gear_ratio = 1.0;
  double delay = 0.0;  ///< tau_p [s]: the drive's delay from the torque command to the measured speed
  /// tau_p + 1.5 T: the delay the loop sees at controller period T.
  double LoopDelay(double period) const { return delay + 1.5 * period; }
};

struct SpeedLoopSettings {
  double period = 0.001;           ///< T [s]; the loop's delay is the plant's + 1.5 T
  double phase_margin_deg = 50.0;  ///< designed for
  double min_gain_margin_db = 6.0;
  double min_modulus_margin = 0.5;
  double notch_width_hz = 0.0;     ///< 0: from the resonance's uncertainty (at least 30 % of it)
  double resonance_std_hz = 0.0;   ///< the fitted resonance's std
  /// Period > 0, phase margin in (0, 90) deg, the rest >= 0.
  bool IsValid(std::string* error) const;
};

/// Margins of C P e^(-(tau_p + 1.5 T) s) on a log grid up to the Nyquist
/// frequency; `stable` from the poles of the sampled loop (DiscreteLoopRadius).
LoopMargins EvaluateSpeedLoop(const SpeedLoopPlant& plant, const PiNotch& controller, double period);

/// The largest magnitude of the closed-loop poles of the sampled loop
/// (below 1: stable): the plant exactly discretised at `period` with its
/// delay tau_p, C(z) of PiNotch::Discrete, the torque applied one period late.
double DiscreteLoopRadius(const SpeedLoopPlant& plant, const PiNotch& controller, double period);

struct SpeedLoopDesign {
  PiNotch controller;
  LoopMargins nominal;
  LoopMargins worst;  ///< over `region` (the nominal when it is empty)
  bool met = false;   ///< every requirement met at the nominal plant
  /// When not met: the largest crossover whose loop meets the margins at the
  /// nominal plant (0: none), and the candidate that came closest.
  double nominal_only_crossover_hz = 0.0;
  LoopMargins closest;
};

/// The largest crossover (PI corner a quarter of it) whose loop meets the
/// phase margin, gain margin and modulus margin at the nominal plant and,
/// over `region` (plants at the edge of the parameters' 95 % region), stays
/// stable with the gain and modulus margins and the phase margin less 10 deg. Throws std::invalid_argument for a
/// plant that is not a two-mass system (non-positive inertias or stiffness).
SpeedLoopDesign DesignSpeedLoop(const SpeedLoopPlant& plant, const std::vector<SpeedLoopPlant>& region,
                                const SpeedLoopSettings& settings);

/// The closed loop's response to a unit step of the speed reference: the
/// plant exactly discretised at `period` (zero-order hold), the controller
/// by Tustin's rule, its torque applied one period late after the plant's
/// delay (whole periods and a fraction, exactly). Motor speed at
/// t = k period for `duration` seconds.
struct StepResponse {
  std::vector<double> time, speed;
};
StepResponse SimulateSpeedStep(const SpeedLoopPlant& plant, const PiNotch& controller, double period, double duration);

/// Open-loop response L(jw) = C P e^(-(tau_p + 1.5 T) s) on `frequencies_hz`.
std::vector<std::complex<double>> OpenLoopResponse(const SpeedLoopPlant& plant, const PiNotch& controller, double period,
                                                   const std::vector<double>& frequencies_hz);

}  // namespace driveid
