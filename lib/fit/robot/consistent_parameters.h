// Physically consistent parameters of a serial robot from its base-parameter
// fit (docs/models.md#physical-consistency). For a linear least-squares fit
// the data's cost about the estimate beta_hat is exactly
//   (beta - beta_hat)^T C^-1 (beta - beta_hat)   (C its covariance),
// so the consistent fit needs no rows: every body's 10 parameters in the
// log-Cholesky form (models/pseudo_inertia.h, physical by construction),
// every drive's armature, viscous and Coulomb >= 0, beta = R theta
// (fit/core/base_parameters.h), and a weak prior towards the URDF's inertials
// (and zero drives) that only settles what the logs do not determine.
// Ceres solves it. Reported: how far the unconstrained estimate lay from the
// consistent set (its cost, in chi^2 units, and the largest shift of a base
// parameter in its std).
#pragma once

#include <string>
#include <vector>

#include "core/fit_result.h"
#include "fit/core/base_parameters.h"
#include "fit/robot/serial_robot_fit.h"
#include "models/serial_robot.h"

namespace driveid {

struct ConsistentParameters {
  std::vector<InertialParameters> bodies;      ///< per joint's body, physical
  std::vector<SerialDriveParameters> drives;   ///< per joint
  std::vector<double> base;                    ///< beta = R theta of these, per base parameter
  double chi2 = 0.0;          ///< (beta - beta_hat)^T C^-1 (beta - beta_hat) over the free ones
  double largest_shift = 0.0; ///< max |beta_j - beta_hat_j| / std_j over the free ones
  std::string largest_shift_name;
  bool converged = false;
  int iterations = 0;
  std::string termination;  ///< the solver's reason for stopping
  /// Joints whose body the URDF gives no mass (no <inertial>): fitted from
  /// kUnknownBody under a prior kUnknownBodyPriorFactor as weak, not a prior
  /// at zero (which collapsed every such body to 1e-18 kg).
  std::vector<std::size_t> unknown_bodies;
};

/// The start and weak prior of a body the URDF gives no mass: 1 kg at the
/// joint, inertia 0.01 kg m^2 about each axis.
inline constexpr InertialParameters kUnknownBody = {1.0, 0.0, 0.0, 0.0, 0.01, 0.0, 0.0, 0.01, 0.0, 0.01};
inline constexpr double kUnknownBodyPriorFactor = 1e-2;

/// The prior's default weight relative to one std of the data (`robot
/// --prior-weight`; docs/models.md#physical-consistency), declared once.
inline constexpr double kConsistentPriorWeight = 1e-4;

/// The prior: the URDF's inertials (the robot's bodies) and its drives,
/// weighted by `weight` relative to one std of the data.
struct ConsistentPrior {
  double weight = kConsistentPriorWeight;     ///< > 0
  std::vector<SerialDriveParameters> drives;  ///< per joint (empty: zero drives)
  /// Whether the values can be used; else `error` names the field and the constraint.
  bool IsValid(std::string* error) const;
};

/// `fit`: the base-parameter fit (its free estimates and covariance); the
/// held base parameters (fit.held) are kept at their values (to 1e-4 of them).
ConsistentParameters FitConsistentParameters(const SerialRobot& robot, const SerialRobotFitOutput& fit,
                                             const ConsistentPrior& prior);

}  // namespace driveid
