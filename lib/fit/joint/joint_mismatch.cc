#include "fit/joint/joint_mismatch.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "fit/core/omitted_terms.h"

namespace driveid {
namespace {

constexpr const char* kStiffness = "stiffness";
constexpr const char* kLargeDeflection = "stiffness above the median deflection";

std::string OrderColumn(int order, bool cosine) { return fmt::format("{} {}", cosine ? "cos" : "sin", order); }

}  // namespace

std::vector<std::string> JointMismatchWarnings(const LinearRegression& regression, const std::vector<std::string>& free,
                                               const std::map<std::string, double>& values,
                                               const std::vector<int>& equation, const std::vector<double>& motor_angle) {
  std::vector<std::string> warnings;
  const std::size_t n = regression.rows();
  if (n == 0 || equation.size() != n || motor_angle.size() != n) return warnings;
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;
  const bool spring_free = std::find(free.begin(), free.end(), kStiffness) != free.end();
  double median = 0.0;
  if (spring_free) {
    const std::size_t k = regression.column(kStiffness);
    std::vector<double> magnitude;
    for (std::size_t r = 0; r < n; ++r) {
      if (regression.at(r, k) != 0.0) magnitude.push_back(std::abs(regression.at(r, k)));
    }
    if (magnitude.size() > 20) {
      std::nth_element(magnitude.begin(), magnitude.begin() + static_cast<std::ptrdiff_t>(magnitude.size() / 2),
                       magnitude.end());
      median = magnitude[magnitude.size() / 2];
      std::vector<double> large(n, 0.0);
      for (std::size_t r = 0; r < n; ++r) {
        if (std::abs(regression.at(r, k)) > median) large[r] = regression.at(r, k);
      }
      names.emplace_back(kLargeDeflection);
      columns.push_back(std::move(large));
    }
  }
  for (int order = 1; order <= kRotationOrders; ++order) {
    for (const bool cosine : {false, true}) {
      std::vector<double> column(n, 0.0);
      for (std::size_t r = 0; r < n; ++r) {
        if (equation[r] == 2) continue;  // the shaft torque sensor sees no motor ripple
        const double phase = order * motor_angle[r];
        column[r] = cosine ? std::cos(phase) : std::sin(phase);
      }
      names.push_back(OrderColumn(order, cosine));
      columns.push_back(std::move(column));
    }
  }
  const LinearRegression extended = regression.WithColumns(names, columns);
  std::map<std::string, double> extended_values = values;
  for (const auto& name : names) extended_values[name] = 0.0;
  if (spring_free && median > 0.0) {
    const OmittedTermTest t = TestOmittedTerm(extended, free, extended_values, "amplitude", {kLargeDeflection}, 0.0);
    const double k = values.at(kStiffness), dk = t.coefficients[0];
    const double std = t.wald > 0.0 ? std::abs(dk) / std::sqrt(t.wald) : 0.0;
    if (t.wald > t.critical && std::abs(dk) >= kAmplitudeStiffnessShare * std::abs(k)) {
      warnings.push_back(fmt::format(
          "model: the joint's stiffness depends on the deflection's amplitude: above the median |deflection| {:.3g} "
          "rad it is {:+.4g} +- {:.2g} ({:+.1f} %) from below it (robust Wald {:.3g} > {:.3g}; the fitted stiffness {:.4g} "
          "averages both): {}; the two-mass model's stiffness, damping and resonance are averages over the logged "
          "amplitudes and may be off by more than their std at any one amplitude",
          median, dk, std, 100.0 * dk / k, t.wald, t.critical, k,
          dk > 0.0 ? "softer at small deflections, as backlash, a dead zone or a hardening spring make it"
                   : "stiffer at small deflections, as a softening spring (or gear friction holding small motions) "
                     "makes it"));
    }
  }
  // The orders found, strongest first; at most kNamedOrders named (a line's
  // modulation by the varying speed leaks into its neighbours).
  constexpr std::size_t kNamedOrders = 3;
  std::vector<std::pair<double, std::string>> found;
  for (int order = 1; order <= kRotationOrders; ++order) {
    const OmittedTermTest t = TestOmittedTerm(extended, free, extended_values, fmt::format("order {}", order),
                                              {OrderColumn(order, false), OrderColumn(order, true)}, kRippleShare);
    if (!t.missing) continue;
    const double amplitude = std::hypot(t.coefficients[0], t.coefficients[1]);
    found.emplace_back(t.share, fmt::format("order {} (amplitude {:.3g}, {:.1f} % of the residual)", order, amplitude,
                                            100.0 * t.share));
  }
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<std::string> orders;
  for (std::size_t i = 0; i < std::min(found.size(), kNamedOrders); ++i) orders.push_back(found[i].second);
  if (found.size() > kNamedOrders) orders.push_back(fmt::format("{} weaker", found.size() - kNamedOrders));
  if (!orders.empty()) {
    warnings.push_back(fmt::format(
        "model: the joint's residual holds lines at {} of the motor's rotation: {}: torque ripple or cogging the "
        "model lacks (amplitudes in the torque equations' units, n tau); the inertias and the resonance may be off by more than "
        "their std",
        orders.size() > 1 ? "orders" : "an order", fmt::join(orders, "; ")));
  }
  return warnings;
}

}  // namespace driveid
