#include "fit/axis/axis_adequacy.h"

#include <algorithm>
#include <cmath>
#include <exception>

#include <fmt/format.h>

#include "core/name_list.h"
#include "fit/axis/axis_rows.h"
#include "fit/core/adequacy.h"
#include "fit/core/omitted_terms.h"
#include "models/axis.h"

namespace driveid {
namespace {

std::vector<std::string> WithFree(const std::vector<std::string>& free, const std::vector<std::string>& more) {
  std::vector<std::string> all = free;
  for (const auto& m : more) {
    if (!Contains(all, m)) all.push_back(m);
  }
  return all;
}

// The free set with the direction-dependent terms in place of coulomb,
// viscous and offset (an offset and both Coulomb directions are collinear).
std::vector<std::string> DirectionFree(const std::vector<std::string>& free) {
  const std::string coulomb = AxisKey(&AxisParameters::coulomb), viscous = AxisKey(&AxisParameters::viscous),
                    offset = AxisKey(&AxisParameters::offset);
  std::vector<std::string> kept;
  for (const auto& f : free) {
    if (f != coulomb && f != viscous && f != offset) kept.push_back(f);
  }
  return WithFree(kept, {AxisKey(&AxisParameters::coulomb_pos), AxisKey(&AxisParameters::coulomb_neg),
                         AxisKey(&AxisParameters::viscous_pos), AxisKey(&AxisParameters::viscous_neg)});
}

// Advice to free more terms is tried before it is given: the fit with
// `trial` free (`zeroed` held at 0, the rest at `values`) must run, be well
// conditioned (collinearity index s_max / s_min of the normalised Jacobian
// below kAdviceCollinearity) and determine each term of `added` (|value|
// above 2 std). Returns "" when it does, else why not.
constexpr double kAdviceCollinearity = 100.0;
std::string TryFreeing(const LinearRegression& regression, const std::vector<std::string>& trial,
                       std::map<std::string, double> values, const std::vector<std::string>& zeroed,
                       const std::vector<std::string>& added) {
  for (const auto& z : zeroed) values[z] = 0.0;
  std::vector<FitParameter> parameters;
  for (const auto& name : trial) {
    const double bound = FindParameter(AxisParameterTable(), name)->spec.lower_bound;
    parameters.push_back({name, std::max(bound, values.at(name)), bound, 0.0});
  }
  FitResult fit;
  try {
    fit = regression.Fit(parameters, values, FitOptions{});
  } catch (const std::exception& e) {
    const std::string what = e.what();
    return what.substr(0, what.find('\n'));
  }
  const auto& s = fit.singular_values;
  if (!s.empty() && !(s.back() * kAdviceCollinearity > s.front())) {
    return fmt::format("the terms would be nearly collinear over these logs (collinearity index {:.3g})",
                       s.back() > 0.0 ? s.front() / s.back() : HUGE_VAL);
  }
  // Some added term must be determined (a gravity amplitude may lie all in
  // cos q), and no non-negative term may become undetermined (the fit would
  // refuse it, docs/models.md#adequacy).
  bool determined = false;
  for (const auto& e : fit.estimates) {
    if (Contains(added, e.name) && std::abs(e.value) > 2.0 * e.standard_error) determined = true;
    const double bound = FindParameter(AxisParameterTable(), e.name)->spec.lower_bound;
    if (bound == 0.0 && e.standard_error > kMaxRelativeStd * std::abs(e.value)) {
      return fmt::format("{} would be {:.4g} +- {:.2g}, not determined", e.name, e.value, e.standard_error);
    }
  }
  if (!determined) return fmt::format("none of {} would be determined", fmt::join(added, ", "));
  return "";
}

}  // namespace

std::vector<std::string> AxisNonnegativeKeys() {
  std::vector<std::string> keys;
  for (std::size_t j = 0; j < AxisParameterCount(); ++j) {
    if (AxisTermRow(j).spec.lower_bound == 0.0) keys.emplace_back(AxisTermRow(j).spec.key);
  }
  return keys;
}

void DecideAxisDetermined(FitResult& fit, double max_relative_std, double rate_variation) {
  std::map<std::string, std::string> silent;
  if (rate_variation >= 0.0 && rate_variation < kAxisMinRateVariation) {
    silent[AxisKey(&AxisParameters::inertia)] = fmt::format(
        "the rate varies within the logs by {:.2g} % of its RMS (below {:g} %): no change of speed for an inertia to "
        "act in; fit friction alone with ‹free› viscous,coulomb,offset",
        100.0 * rate_variation, 100.0 * kAxisMinRateVariation);
  }
  BoundOrRefuse(fit, AxisNonnegativeKeys(), max_relative_std, fit.warnings, silent);
}

std::vector<std::string> CheckAxisAdequacy(const LinearRegression& regression, const FitResult& fit,
                                           const std::vector<std::string>& free,
                                           const std::map<std::string, double>& values, bool linear) {
  std::vector<std::string> warnings = fit.warnings;  // the core's (low fit)
  const auto evidence = [](const OmittedTermTest& t) {
    return fmt::format("explain {:.0f} % of the residual; robust Wald {:.3g} > {:.3g}", 100.0 * t.share, t.wald,
                       t.critical);
  };
  const std::string gravity_cos = AxisKey(&AxisParameters::gravity_cos), gravity_sin = AxisKey(&AxisParameters::gravity_sin);
  const std::string inertia = AxisKey(&AxisParameters::inertia);
  if (!linear && !Contains(free, gravity_cos) && !Contains(free, gravity_sin)) {
    const auto t = TestOmittedTerm(regression, free, values, "gravity", {gravity_cos, gravity_sin});
    if (t.missing) {
      const auto trial = WithFree(free, {gravity_cos, gravity_sin});
      const std::string why_not = TryFreeing(regression, trial, values, {}, {gravity_cos, gravity_sin});
      warnings.push_back(
          why_not.empty()
              ? fmt::format("gravity missing?: the residual follows the position (cos q and sin q {}): try the "
                            "gravity term: ‹free› {}",
                            evidence(t), fmt::join(trial, ","))
              : fmt::format("position-dependent force: the residual follows the position (cos q and sin q {}), but "
                            "the gravity terms would not be identifiable from these logs ({}): log a wider range of "
                            "q; a linear axis (axis.linear: true, ‹linear›) has its weight in the offset",
                            evidence(t), why_not));
    }
  }
  if (!Contains(free, inertia)) {
    const auto t = TestOmittedTerm(regression, free, values, "inertia", {inertia});
    if (t.missing) {
      const auto trial = WithFree(free, {inertia});
      const std::string why_not = TryFreeing(regression, trial, values, {}, {inertia});
      warnings.push_back(fmt::format("inertia: the residual follows the acceleration (q'' {}): the fixed J = {:.4g} is "
                                     "off{}",
                                     evidence(t), values.at(inertia),
                                     why_not.empty() ? fmt::format(": try ‹free› {}", fmt::join(trial, ","))
                                                     : fmt::format(" (freeing it would not help: {})", why_not)));
    }
  }
  const auto direction = TestOmittedTerm(regression, free, values, "direction", {kAxisAbsRateColumn});
  if (direction.missing) {
    const auto trial = DirectionFree(free);
    const std::vector<std::string> replaced = {AxisKey(&AxisParameters::coulomb), AxisKey(&AxisParameters::viscous),
                                               AxisKey(&AxisParameters::offset)};
    const std::string why_not =
        TryFreeing(regression, trial, values, replaced,
                   {AxisKey(&AxisParameters::coulomb_pos), AxisKey(&AxisParameters::coulomb_neg)});
    warnings.push_back(
        why_not.empty()
            ? fmt::format("direction-dependent friction: the residual follows |q'| ({}): friction differs between "
                          "the directions of motion: try the direction-dependent terms in place of coulomb, viscous "
                          "and the offset they absorb: ‹free› {}",
                          evidence(direction), fmt::join(trial, ","))
            : fmt::format("direction-dependent friction: the residual follows |q'| ({}), but the direction-dependent "
                          "terms would not be identifiable from these logs ({}): log motion in both directions",
                          evidence(direction), why_not));
  }
  const auto drift = TestOmittedTerm(regression, free, values, "drift", {kAxisTimeColumn});
  if (drift.missing) {
    warnings.push_back(fmt::format("drift: the residual follows time within the logs ({}): friction or a sensor "
                                   "changed during the log (warm-up?); fit shorter windows with ‹from›/‹to›",
                                   evidence(drift)));
  }
  return warnings;
}

}  // namespace driveid
