#include "design/nelder_mead.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace driveid {

SimplexResult MinimiseNelderMead(const std::function<double(const std::vector<double>&)>& f,
                                 const std::vector<double>& x0, const std::vector<double>& step, double tolerance,
                                 int max_evaluations) {
  const std::size_t n = x0.size();
  // Gao and Han's coefficients: the classic (2, 1/2, 1/2) expand and shrink
  // too hard once n passes a few dimensions and the simplex collapses onto a
  // subspace; theirs tend to the classic ones at n = 2 (n < 2 is treated as 2).
  const double dn = static_cast<double>(std::max<std::size_t>(n, 2));
  const double expand = 1.0 + 2.0 / dn, contract = 0.75 - 0.5 / dn, shrink = 1.0 - 1.0 / dn;
  std::vector<std::vector<double>> points(n + 1, x0);
  std::vector<double> values(n + 1);
  int evaluations = 0;
  auto eval = [&](const std::vector<double>& x) {
    ++evaluations;
    const double v = f(x);
    // A point the objective cannot evaluate (a design past a limit) ranks
    // worst instead of poisoning the ordering with NaN.
    return std::isfinite(v) ? v : HUGE_VAL;
  };
  // The start simplex: x0 and one vertex a step along each coordinate.
  for (std::size_t i = 0; i < n; ++i) points[i + 1][i] += step[i];
  for (std::size_t i = 0; i <= n; ++i) values[i] = eval(points[i]);
  std::vector<std::size_t> order(n + 1);
  auto along = [&](const std::vector<double>& centre, const std::vector<double>& worst, double t) {
    std::vector<double> x(n);
    for (std::size_t j = 0; j < n; ++j) x[j] = centre[j] + t * (worst[j] - centre[j]);
    return x;
  };
  while (evaluations < max_evaluations) {
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
    const std::size_t best = order.front(), worst = order.back(), second = order[n - 1];
    if (!(values[worst] - values[best] > tolerance)) break;
    // Centroid of all vertices but the worst, the pivot of every move.
    std::vector<double> centre(n, 0.0);
    for (std::size_t i = 0; i <= n; ++i) {
      if (i == worst) continue;
      for (std::size_t j = 0; j < n; ++j) centre[j] += points[i][j] / static_cast<double>(n);
    }
    const auto reflected = along(centre, points[worst], -1.0);
    const double fr = eval(reflected);
    // Reflected past the best: try going twice as far (expansion) and keep
    // the better of the two (greedy minimisation, Lagarias et al. 1998).
    if (fr < values[best]) {
      const auto expanded = along(centre, points[worst], -expand);
      const double fe = eval(expanded);
      points[worst] = fe < fr ? expanded : reflected;
      values[worst] = std::min(fe, fr);
      continue;
    }
    if (fr < values[second]) {
      points[worst] = reflected;
      values[worst] = fr;
      continue;
    }
    // Reflection not better than the second worst: contract towards the
    // centroid, on the reflected side if it improved on the worst (outside),
    // else on the worst's side (inside).
    const bool outside = fr < values[worst];
    const auto contracted = along(centre, outside ? reflected : points[worst], contract);
    const double fc = eval(contracted);
    if (fc < std::min(fr, values[worst])) {
      points[worst] = contracted;
      values[worst] = fc;
      continue;
    }
    // No contraction helped: the minimum lies inside a smaller simplex;
    // shrink every vertex towards the best.
    for (std::size_t i = 0; i <= n; ++i) {
      if (i == best) continue;
      for (std::size_t j = 0; j < n; ++j) points[i][j] = points[best][j] + shrink * (points[i][j] - points[best][j]);
      values[i] = eval(points[i]);
    }
  }
  const auto best = static_cast<std::size_t>(std::min_element(values.begin(), values.end()) - values.begin());
  return {points[best], values[best], evaluations};
}

}  // namespace driveid
