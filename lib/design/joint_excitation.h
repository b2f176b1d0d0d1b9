// Excitation design for the elastic joint (docs/models.md#joint-excitation-design):
// a periodic torque multisine injected at the motor whose line powers make
// the frequency-response fit (fit/frf/frequency_response_fit.h, `frf --fit
// two-mass`) of its log determine the free parameters best, within the
// torque and motor-speed limits.
//
// Prediction. A multisine of period P = N / f_s with line amplitudes A_l at
// w_l = 2 pi l / P, logged for M + 1 periods (the first settles and is left
// out), motor-speed noise of std sigma_v and logged-torque noise of std
// sigma_u per sample (white). The periodic estimate's error at line l is
// complex with Var(H_l) / |H_l|^2 = 4 s_l^2 / (M N A_l^2),
// s_l^2 = sigma_v^2 / |H_l|^2 + sigma_u^2, half in ln|H| and half in the
// phase, so the fit's information on the relative parameters x_j = ln p_j is
//   F = sum_l (M N A_l^2 / (2 s_l^2)) Re(g_l g_l^H),
//   g_l = d ln H(w_l) / d ln p   (models/joint.h, CalcJointResponse),
// with H the motor rate per logged torque, and Cov(p_j) = p_j^2 (F^-1)_jj.
//
// Design. F is linear in the line powers w_l = A_l^2 / (2 R^2) (their share
// of the mean-square torque R^2), so the D-optimal shares maximise
// log det F(w) over the simplex: the multiplicative algorithm
// w_l <- w_l tr(F^-1 F_l) / m (Titterington), whose fixed point meets the
// equivalence theorem max_l tr(F^-1 F_l) = m; A-optimal for target
// parameters: w_l <- w_l sqrt(tr(W F^-1 F_l F^-1)) normalised. A share
// `spread` of the power stays spread evenly over the band, so that a prior
// whose resonance is off still finds lines around it. Phases by Schroeder's
// rule for unequal powers, then lowered by clipping and re-phasing (the
// lines' amplitudes kept; lower crest factor). The rms R is then the
// largest that keeps the peak torque within T and the prior's peak motor
// speed within V. The naive excitation it is compared with: the default
// multisine of `simulate joint` (every line of the band, equal amplitudes,
// Schroeder phases) at the same rms.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "models/joint.h"

namespace driveid {

/// The injected torque is met to kJointTorqueMargin of its limit (it is
/// what is injected), the prior's predicted motor speed to kJointSpeedMargin.
inline constexpr double kJointTorqueMargin = 0.99;
inline constexpr double kJointSpeedMargin = 0.95;

struct JointDesignOptions {
  std::vector<std::string> free = TwoMassDefaultFree();
  double duration = 0.0;               ///< log length [s] (whole periods)
  double rate = 1000.0;                ///< logging rate [Hz]
  double period = 2.0;                 ///< multisine period [s]
  double band_low = 0.5, band_high = 50.0;  ///< lines between [Hz]
  double max_torque = 0.0;             ///< T: |tau| limit [N m, log units]
  double max_speed = 0.0;              ///< V: |qd_motor| limit of the prior [rad/s, log units]
  double noise = 0.0;                  ///< sigma_v: motor-speed noise per sample [rad/s]
  double torque_noise = 0.0;           ///< sigma_u: logged-torque noise per sample [N m]
  std::string criterion = "d";         ///< d or a
  std::vector<std::string> targets;    ///< the parameters that count (D_s: the others are nuisance; default: all free)
  double spread = 0.2;                 ///< share of the power spread evenly over the band
  bool IsValid(std::string* error) const;
};

struct JointDesignCandidate {
  std::string name;                    ///< "designed" or "default multisine"
  std::vector<double> amplitude, phase;  ///< per line [N m, rad]
  double rms = 0.0;                    ///< [N m]
  double peak_torque = 0.0, peak_speed = 0.0;  ///< over one period on the logging grid
  std::string binding;                 ///< the limit that sets the rms ("" for the naive: same rms)
  Eigen::MatrixXd covariance;          ///< predicted, free parameters in `free` order
  std::vector<double> predicted_std;
  double geometric_mean_relative_std = 0.0;
};

struct JointDesign {
  std::vector<std::string> free;
  std::vector<double> prior;           ///< the free parameters' prior values
  std::vector<double> frequency;       ///< the band's lines [Hz]
  double period = 0.0, noise = 0.0, torque_noise = 0.0, gear_ratio = 1.0;
  int periods = 0;                     ///< whole periods in the log (the first settles)
  int iterations = 0;                  ///< of the multiplicative algorithm
  double equivalence = 0.0;            ///< max_l tr(F^-1 F_l) / m at the D-optimum (1 there)
  JointDesignCandidate designed, naive;
  /// The rms the default multisine could have within the same limits (its
  /// stds scale with 1 / rms): the comparison at the limits, not at equal rms.
  double naive_rms_at_limits = 0.0;
};

/// Designs the multisine. Throws OptionError naming a bad option and
/// InputError for a prior that cannot predict (a free parameter whose prior
/// value is not positive); a free parameter that is not a dynamic term is an
/// OptionError.
JointDesign DesignJointExcitation(const JointParameters& prior, double gear_ratio, const JointDesignOptions& options);

/// The candidate's torque at the logging rate over `duration` [s].
std::vector<double> SampleJointExcitation(const JointDesign& design, const JointDesignCandidate& candidate,
                                          double rate, double duration);

}  // namespace driveid
