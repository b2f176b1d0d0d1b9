// Excitation design for a serial robot (docs/models.md#serial-robot-excitation):
// one periodic Fourier trajectory per joint (design/fourier_reference.h,
// Swevers et al. 1997: lines 1..K of f_0 = 1 / period, starting and ending
// at rest at a start pose), chosen so that the fit of its log
// (fit/robot/serial_robot_fit.h) determines the base parameters best while every
// joint stays within its limits along the whole trajectory.
//
// Prediction. The fit regresses joint j's torque on the base regressor's
// rows W_j(q, q', q'') (the base columns of models/serial_dynamics.h's
// regressor), weighted by 1 / sigma_j; for N = T f_s samples
//   Cov(beta) = (N / M sum_{m=1..M} sum_j W_j(t_m)' W_j(t_m) / sigma_j^2)^-1
// over M grid points of one period. sigma_j is the joint's torque noise per
// sample as the fit meets it (its residual rmse times its inflation for
// coloured residuals, docs/models.md#identification).
//
// Limits. Each joint's trajectory is scaled to the largest amplitude that
// keeps its range inside [lower, upper] (the start pose centres it there)
// or within +-Q of the start, |q'| <= V and |q''| <= A (met to
// kKinematicMargin); then all scales shrink by one common factor until every
// joint's predicted torque (the prior's bodies and drives) stays within
// kTorqueMargin of its effort limit. URDF limits apply unless the options
// give tighter ones.
//
// Criterion, minimised over the shapes by Nelder-Mead:
//   D: -log det of the information (the geometric-mean std of the base
//      parameters, up to a constant);
//   A: sum of Var(beta_j) / s_j^2, s_j = |prior beta_j| (at least 1e-3 of
//      the largest): the relative variances.
// Reported beside it: the condition number of the column-normalised
// weighted base regressor, as FIGAROH reports for its designs.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "design/fourier_reference.h"
#include "models/serial_robot.h"

namespace driveid {

struct RobotDesignOptions {
  double duration = 0.0;         ///< log length T [s]
  double rate = 100.0;           ///< logging rate f_s [Hz]
  double period = 0.0;           ///< [s]; 0: the duration split into periods of at most 10 s
  int harmonics = 5;             ///< K lines per joint
  double max_position = 0.0;     ///< Q [rad or m] about the start; 0: the URDF's range only
  double max_rate = 0.0;         ///< V; 0: the URDF's velocity limits
  double max_acceleration = 0.0; ///< A; 0: none (the torque's)
  double max_torque = 0.0;       ///< T; 0: the URDF's effort limits
  std::string criterion = "d";   ///< d or a
  int evaluations = 4000;        ///< of the optimiser, per start (2 starts)
  bool IsValid(std::string* error) const;
};

struct RobotDesignJoint {
  std::string name;
  FourierReference reference;   ///< about the start, at its scale
  double start = 0.0;           ///< start (and end) pose [rad or m]
  std::string binding;          ///< the limit that sets its amplitude
  double lowest = 0.0, highest = 0.0, peak_rate = 0.0, peak_acceleration = 0.0, peak_torque = 0.0;
  double rate_limit = 0.0, torque_limit = 0.0;  ///< the limits applied (infinite: none)
};

struct RobotDesign {
  std::vector<RobotDesignJoint> joints;
  double period = 0.0;
  Eigen::MatrixXd covariance;       ///< of the base parameters, predicted
  std::vector<double> predicted_std;
  double condition_number = 0.0;    ///< of the column-normalised weighted base regressor
  double criterion = 0.0;
  int evaluations = 0;
};

/// `theta` the prior's full parameter vector (models/serial_dynamics.h),
/// `base_columns` the base parameters' lead columns, `noise` sigma_j per
/// joint [N m or N]. Throws OptionError naming the option or joint when a
/// joint has no position range (continuous, no ‹max_position›), no rate
/// limit, or the prior's torque at rest already exceeds a limit.
RobotDesign DesignRobotExcitation(const SerialRobot& robot, const Eigen::VectorXd& theta,
                                  const std::vector<std::size_t>& base_columns, const std::vector<double>& noise,
                                  const RobotDesignOptions& options);

/// The trajectory on the logging grid t_k = k / f_s, 0 <= t_k <= T:
/// q, q', q'' per joint (q including the start pose).
struct SampledRobotTrajectory {
  std::vector<double> time;
  std::vector<std::vector<double>> position, rate, acceleration;  ///< [joint][sample]
};
SampledRobotTrajectory SampleRobotTrajectory(const RobotDesign& design, double rate, double duration);

}  // namespace driveid
