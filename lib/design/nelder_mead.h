// Derivative-free minimisation by the Nelder-Mead simplex with the
// dimension-adapted coefficients of Gao and Han (2012): reflection 1,
// expansion 1 + 2/n, contraction 0.75 - 1/(2n), shrink 1 - 1/n. For the
// excitation design, whose objective (information at the largest amplitude
// the limits allow) has kinks where the binding limit changes.
#pragma once

#include <functional>
#include <vector>

namespace driveid {

struct SimplexResult {
  std::vector<double> x;
  double value = 0.0;
  int evaluations = 0;
};

/// Minimises f from x0 with initial steps `step` per coordinate, until the
/// simplex's values span less than `tolerance` (absolute) or after
/// `max_evaluations`.
SimplexResult MinimiseNelderMead(const std::function<double(const std::vector<double>&)>& f,
                                 const std::vector<double>& x0, const std::vector<double>& step, double tolerance,
                                 int max_evaluations);

}  // namespace driveid
