// Identification of a serial robot's rigid-body model and drives
// (docs/models.md#serial-robot) from logged joint positions (and rates
// where logged) and joint torques, by inverse dynamics on its base
// parameters (fit/core/base_parameters.h):
//   tau_i(t_k) = sum_j W_b,ij(q, q', q'') beta_j + e_i(t_k)
// Rates come from the log or, like accelerations, from the zero-phase
// local-polynomial differentiator (signal/local_polynomial.h). The joints'
// noise differs (a base joint's torque is tens of N m, a wrist's a few):
// each joint's rows are weighted by 1 / its residual std from an
// unweighted first solve, and the fit core's intervals account for
// coloured residuals per joint (docs/models.md#identification).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/fit_result.h"
#include "core/fit_options.h"
#include "fit/core/base_parameters.h"
#include "logs/serial_robot_log.h"
#include "models/serial_robot.h"

namespace driveid {

struct SerialRobotFitOptions {
  double half_window = 0.05;  ///< differentiator half window [s]
  FitOptions fit;
  /// The base parameters to estimate (empty: all): each by its lead's name
  /// (`Izz_link1`, `viscous_joint_2`), or `bodies` / `drives` for every one
  /// led by an inertial / a drive column. The others are held at the prior's
  /// value, beta = R theta_prior (docs/models.md#serial-robot-identification).
  std::vector<std::string> free;
  /// The prior's drives per joint (the URDF's <dynamics>; empty: zero), its
  /// bodies the robot's inertials.
  std::vector<SerialDriveParameters> prior_drives;
  /// Whether the values can be used; else `error` names the field and the constraint.
  bool IsValid(std::string* error) const;
};

/// A joint's torque prediction on the logs it was fitted to (or validated on).
struct SerialJointStatistics {
  std::string joint;
  double rmse = 0.0;                    ///< [N m or N]
  double fit_percent = 0.0;             ///< 100 (1 - |e| / |tau - mean tau|)
  double relative_error_percent = 0.0;  ///< 100 |e| / |tau|
  double weight_std = 0.0;              ///< the residual std its rows were weighted by
};

struct SerialRobotFitOutput {
  BaseParameters base;
  std::vector<std::string> parameter_names;  ///< of the full theta (models/serial_dynamics.h)
  FitResult fit;                             ///< estimates of the free base parameters, named by their lead column
  std::vector<std::size_t> free;             ///< the estimated base parameters (indices into base), fit's order
  std::vector<double> held;                  ///< per base parameter: its prior value where held, NaN where free
  std::vector<SerialJointStatistics> joints;
  double condition_number = 0.0;  ///< of the logs' column-normalised base regressor
  std::size_t samples = 0;        ///< samples used (valid differentiator windows)
  /// Every base parameter's value: its estimate where free, else held.
  std::vector<double> BaseValues() const;
};

/// The base parameters `names` select (SerialRobotFitOptions::free; empty:
/// all), in base order. OptionError naming an unknown name or a parameter
/// that is not a base parameter's lead (and the one it belongs to).
std::vector<std::size_t> SelectSerialBaseParameters(const BaseParameters& base,
                                                    const std::vector<std::string>& parameter_names,
                                                    const std::vector<std::string>& names);

/// Throws InputError for logs that do not fit the robot, IdentificationError
/// (naming the base parameters) when the logs do not determine them.
SerialRobotFitOutput FitSerialRobot(const SerialRobot& robot, const std::vector<SerialRobotLog>& logs,
                                    const SerialRobotFitOptions& options);

/// A log's q, q', q'' at the samples where every joint's differentiator
/// window (half width `half_window` [s]) is centred: rates as logged where
/// logged. InputError for a log that does not fit the robot.
struct SerialMotion {
  std::vector<std::size_t> sample;  ///< index into the log
  std::vector<double> time;         ///< [s]
  std::vector<Eigen::VectorXd> q, qd, qdd;
};
SerialMotion DifferentiateSerialLog(const SerialRobot& robot, const SerialRobotLog& log, double half_window);

/// The base parameters of `robot` (its structure, on random motions).
BaseParameters SerialBaseParameters(const SerialRobot& robot);

/// The largest of the logs' median sample steps [s] (0 for logs of one
/// sample): the slowest log, which a differentiator's window must span.
double SlowestSerialLogStep(const std::vector<SerialRobotLog>& logs);

/// A joint's RMSE, fit % and relative error of `predicted` against `measured`.
SerialJointStatistics CalcSerialJointStatistics(const std::string& joint, const std::vector<double>& measured,
                                                const std::vector<double>& predicted);

/// Each joint's predicted torque along a log from base-parameter values
/// (`base.base` lead columns, `values` in that order), and its statistics.
struct SerialPrediction {
  std::vector<double> time;
  std::vector<std::vector<double>> measured, predicted;  ///< [joint][sample]
  std::vector<SerialJointStatistics> joints;
};
SerialPrediction PredictSerialRobot(const SerialRobot& robot, const BaseParameters& base,
                                    const std::vector<double>& values, const SerialRobotLog& log, double half_window);

}  // namespace driveid
