// Student's t quantile for the intervals every fit reports (Boost.Math).
#pragma once

namespace driveid {

/// Two-sided 97.5 % quantile of Student's t with `dof` degrees of freedom
/// (infinity for dof < 1).
double StudentT975(int dof);

}  // namespace driveid
