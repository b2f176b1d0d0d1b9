// Effects the two-mass joint model lacks (docs/models.md#elastic-joint,
// "what the model lacks"), named from the inverse-dynamics joint fit's rows
// by the omitted-term test (fit/core/omitted_terms.h: the candidate's columns
// projected off the fitted ones, a robust Wald test at 0.999):
// - a stiffness that depends on the deflection's amplitude (backlash, a
//   dead zone, a hardening or softening spring): the spring column split at
//   the median |deflection|, k D for the small half and (k + dk) D for the
//   large one; named when dk is significant and at least
//   kAmplitudeStiffnessShare of k;
// - torque ripple or cogging at an order j of the motor's rotation:
//   sin(j phi), cos(j phi) of the motor shaft angle phi on the torque
//   equations' rows, j = 1 .. kRotationOrders, each tested alone; named
//   when significant and explaining at least kRippleShare of the residual.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "fit/core/linear_regression.h"

namespace driveid {

inline constexpr double kAmplitudeStiffnessShare = 0.02;
inline constexpr int kRotationOrders = 12;
inline constexpr double kRippleShare = 0.01;
/// How each of these warnings begins.
inline constexpr const char* kJointMismatchPrefix = "model: the joint's ";

/// The fitted regression (its free columns `free`, every column's value in
/// `values`), each row's equation (0 motor, 1 total, 2 shaft torque) and
/// motor shaft angle [rad]; one warning per effect found.
std::vector<std::string> JointMismatchWarnings(const LinearRegression& regression, const std::vector<std::string>& free,
                                               const std::map<std::string, double>& values,
                                               const std::vector<int>& equation, const std::vector<double>& motor_angle);

}  // namespace driveid
