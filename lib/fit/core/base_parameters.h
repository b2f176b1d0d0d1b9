// Base parameters of a linear model tau = W theta (docs/models.md#base-parameters):
// the combinations of theta that W determines. Columns that are zero for
// every motion never reach the torque; a column that is a combination of
// earlier ones (W_d = W_b B, found on regressor rows of random motions, so
// that the structure, not one trajectory, decides) is regrouped into them:
//   W theta = W_b (theta_b + B theta_d) = W_b beta.
// The columns are taken in order, each kept when it adds a direction the
// kept ones do not span (Gram-Schmidt on unit columns), so a joint's
// parameters regroup into the earlier links' (Khalil's rules, found
// numerically; an armature joins its link's inertia about the same axis).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace driveid {

struct BaseParameters {
  std::vector<std::size_t> base;          ///< each base parameter's lead column in theta
  std::vector<std::size_t> never_moved;   ///< columns that are zero in every row
  Eigen::MatrixXd regroup;                ///< r x P: beta = regroup theta
  std::vector<std::string> names;         ///< "Izz_upper + armature_shoulder + 0.7 m_lower"
  /// The combination of each base parameter: (column, coefficient), lead first.
  std::vector<std::vector<std::pair<std::size_t, double>>> combination;
};

/// From rows `w` of random motions (rows >= columns) and the columns' names.
/// `tolerance`: a column is new when its part outside the kept ones' span
/// exceeds this fraction of its norm.
BaseParameters FindBaseParameters(const Eigen::MatrixXd& w, const std::vector<std::string>& names,
                                  double tolerance = 1e-6);

/// "lead + c name + ..." of a combination, coefficients to 4 digits.
std::string CombinationName(const std::vector<std::pair<std::size_t, double>>& combination,
                            const std::vector<std::string>& names);

}  // namespace driveid
