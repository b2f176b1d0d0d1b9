#include "workflow/axis_feedforward.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace driveid {

double PropagateStandardError(const FitResult& fit, const std::vector<std::pair<std::string, double>>& gradient) {
  const std::size_t n = fit.estimates.size();
  std::vector<double> g(n, 0.0);
  for (const auto& [name, derivative] : gradient) {
    for (std::size_t i = 0; i < n; ++i) {
      if (fit.estimates[i].name == name) g[i] += derivative;
    }
  }
  double variance = 0.0;
  if (fit.covariance.size() == n * n) {
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = 0; j < n; ++j) variance += g[i] * fit.covariance[i * n + j] * g[j];
    }
  }
  return std::sqrt(std::max(0.0, variance));
}

namespace {

bool Estimated(const FitResult& fit, double AxisParameters::*member) {
  return std::any_of(fit.estimates.begin(), fit.estimates.end(),
                     [&](const ParameterEstimate& e) { return e.name == AxisKey(member); });
}

}  // namespace

Feedforward CalcAxisFeedforward(const AxisParameters& p, const FitResult& fit, const std::string& effort_unit,
                                const std::string& position_unit, bool with_inertia) {
  using P = AxisParameters;
  Feedforward out{kAxisFeedforwardLaw, effort_unit, position_unit, {}};
  const auto used = [&](double P::*member) { return Estimated(fit, member) || p.*member != 0.0; };
  const auto add = [&](const std::string& key, double value, std::vector<std::pair<std::string, double>> gradient) {
    out.gains.push_back(
        {key, value, PropagateStandardError(fit, gradient), FeedforwardUnit(key, effort_unit, position_unit)});
  };
  if (used(&P::coulomb_pos) || used(&P::coulomb_neg)) {
    add("Ks_forward", p.coulomb + p.coulomb_pos, {{AxisKey(&P::coulomb), 1.0}, {AxisKey(&P::coulomb_pos), 1.0}});
    add("Ks_backward", p.coulomb + p.coulomb_neg, {{AxisKey(&P::coulomb), 1.0}, {AxisKey(&P::coulomb_neg), 1.0}});
  } else {
    add("Ks", p.coulomb, {{AxisKey(&P::coulomb), 1.0}});
  }
  if (used(&P::viscous_pos) || used(&P::viscous_neg)) {
    add("Kv_forward", p.viscous + p.viscous_pos, {{AxisKey(&P::viscous), 1.0}, {AxisKey(&P::viscous_pos), 1.0}});
    add("Kv_backward", p.viscous + p.viscous_neg, {{AxisKey(&P::viscous), 1.0}, {AxisKey(&P::viscous_neg), 1.0}});
  } else {
    add("Kv", p.viscous, {{AxisKey(&P::viscous), 1.0}});
  }
  if (with_inertia) add("Ka", p.inertia, {{AxisKey(&P::inertia), 1.0}});
  if (used(&P::gravity_cos) || used(&P::gravity_sin)) {
    // Kg cos(q - Kg_angle) = Kg cos(Kg_angle) cos q + Kg sin(Kg_angle) sin q.
    const double gc = p.gravity_cos, gs = p.gravity_sin, kg = std::hypot(gc, gs);
    const double k2 = kg > 0.0 ? kg * kg : 1.0;
    add("Kg", kg, {{AxisKey(&P::gravity_cos), kg > 0.0 ? gc / kg : 0.0}, {AxisKey(&P::gravity_sin), kg > 0.0 ? gs / kg : 0.0}});
    add("Kg_angle", std::atan2(gs, gc), {{AxisKey(&P::gravity_cos), -gs / k2}, {AxisKey(&P::gravity_sin), gc / k2}});
  }
  if (used(&P::offset)) add("offset", p.offset, {{AxisKey(&P::offset), 1.0}});
  return out;
}

}  // namespace driveid
