// Excitation design for a rigid axis (docs/models.md#excitation-design): a
// periodic position reference (design/fourier_reference.h) that the axis's
// position loop follows, chosen so that the inverse-dynamics fit
// (fit/axis/axis_fit.h) of its log determines the free parameters best while
// every limit holds along the whole reference.
//
// Prediction. The fit regresses tau = phi(q, q', q'')' p on samples
// decimated by d = 10 after a low-pass at 0.8 of their Nyquist frequency; a
// torque noise of std sigma per logged sample (white) leaves sigma^2 0.8 / d
// per decimated sample, so for a log of duration T at rate f_s
//   Cov(p) = sigma^2 0.8 / d (sum_decimated phi phi')^-1
//          ~ sigma^2 0.8 / f_s (integral_0^T phi phi' dt)^-1,
// the integral taken over one period times T / period, leaving out the
// samples the fit leaves out (|q'| below 1 % of its largest).
//
// Design. For a shape x (the coefficients of lines 2..K) the reference is
// scaled to the largest amplitude s that keeps |q| <= Q, |q'| <= V,
// |q''| <= A and the prior model's torque |tau(q, q', q'')| <= T (with the
// margins below); the criterion is evaluated at that amplitude and
// minimised over x by Nelder-Mead from several starts:
//   D: -log det of the information of the free parameters (each scaled by
//      its prior value), i.e. the geometric-mean std;
//   A: sum over the target parameters of Var(p_j) / p_j^2 (relative).
// The naive reference it is compared with, the hand-made test it replaces:
// four sines of equal amplitude at 0.2, 0.43, 0.93 and 2 Hz (rounded to
// harmonics of 1 / period), scaled to the same limits.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "design/fourier_reference.h"
#include "models/axis.h"

namespace driveid {

/// Kinematic limits are met to this fraction, the torque to kTorqueMargin
/// (the prior's torque is a prediction).
inline constexpr double kKinematicMargin = 0.99;
inline constexpr double kTorqueMargin = 0.95;
/// The fit's decimation and its filter's share of the decimated band.
inline constexpr double kDesignDecimation = 10.0;
inline constexpr double kDesignDecimationBand = 0.8;
/// The fit leaves out this many decimations' samples on each side of a
/// sample slower than 1 % of the largest rate at the band cutoff (fit/axis/axis_rows.h
/// AxisExclusionReach; tests/design/axis_excitation_test.cc checks they agree).
inline constexpr int kDesignExclusionDecimations = 4;

struct AxisDesignOptions {
  std::vector<std::string> free = FitParameterKeys(AxisParameterTable(), "axis", true);
  double duration = 0.0;     ///< log length [s]
  double rate = 1000.0;      ///< logging rate [Hz]
  double period = 0.0;       ///< reference period [s]; 0: the best of duration / (m ceil(duration / 10 s)), m = 1, 2, 4
  double band_low = 0.0;     ///< lowest line [Hz]; 0: the fundamental
  double band_high = 0.0;    ///< highest line [Hz]; 0: from the limits (below rate / 150)
  int lines = 10;            ///< at most this many lines in the band
  double max_position = 0.0;      ///< Q [rad or m], about the start
  double max_rate = 0.0;          ///< V [rad/s or m/s]
  double max_acceleration = 0.0;  ///< A [rad/s^2 or m/s^2]; 0: the torque's only
  double max_torque = 0.0;        ///< T [N m or N]
  std::string criterion = "d";    ///< d or a
  std::vector<std::string> targets;  ///< A: the parameters whose variances count (default: all free)
  double noise = 0.0;             ///< sigma: torque noise per logged sample [N m]
  int evaluations = 3000;         ///< per start of the optimiser (6 starts)
  bool IsValid(std::string* error) const;
};

struct AxisDesignPeaks {
  double position = 0.0, rate = 0.0, acceleration = 0.0, torque = 0.0;
};

struct AxisDesignCandidate {
  std::string name;             ///< "designed" or "four sines"
  FourierReference reference;   ///< at its scale
  std::string binding;          ///< the limit that sets the amplitude
  AxisDesignPeaks peaks;        ///< over one period on the logging grid
  Eigen::MatrixXd covariance;   ///< predicted, free parameters in `free` order
  std::vector<double> predicted_std;
  double geometric_mean_relative_std = 0.0;  ///< (prod std_j / |p_j|)^(1/n)
};

struct AxisDesign {
  std::vector<std::string> free;
  std::vector<double> prior;    ///< the free parameters' prior values
  double period = 0.0, band_low = 0.0, band_high = 0.0, noise = 0.0;
  AxisDesignCandidate designed, naive;
  int evaluations = 0;
};

/// Designs the reference. Throws OptionError naming a bad option (a limit
/// the prior's friction alone exceeds, a band without two lines) and
/// InputError for a prior that cannot predict (a free parameter outside the
/// linear terms: a nonlinear term's).
AxisDesign DesignAxisExcitation(const AxisParameters& prior, const AxisDesignOptions& options);

/// The torque noise per logged sample [N m] that an inverse-dynamics fit's
/// residuals show (fit.rmse, fit.inflation of its ":tau" channels; the
/// median over logs): rmse x inflation x sqrt(d / 0.8), the decimated
/// residual's band undone. 0 when there is none (an output-error fit).
double NoiseFromIdimResiduals(const std::vector<std::pair<std::string, double>>& rmse,
                              const std::vector<std::pair<std::string, double>>& inflation);

/// The samples of a reference on the logging grid: t, q, q', q'' and the
/// prior's torque.
struct SampledReference {
  std::vector<double> time, position, rate, acceleration, torque;
};
SampledReference SampleReference(const FourierReference& reference, const AxisParameters& prior, double rate,
                                 double duration);

}  // namespace driveid
