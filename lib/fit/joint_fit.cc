#include "fit/joint_fit.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "core/errors.h"
#include "fit/adequacy.h"
#include "fit/axis_rows.h"
#include "fit/linear_regression.h"
#include "signal/butterworth.h"

namespace driveid {
namespace {

std::vector<std::string> JointColumnNames() {
  std::vector<std::string> names;
  for (const auto& row : JointParameterTable()) {
    if (row.in_model != nullptr) names.emplace_back(row.spec.key);
  }
  return names;
}

std::string JointAdvice(const std::vector<std::string>& involved) {
  std::vector<std::string> advice;
  const auto has = [&](const char* key) { return std::find(involved.begin(), involved.end(), key) != involved.end(); };
  if (has("stiffness") || has("damping")) {
    advice.push_back("stiffness and damping need a deflection q_motor/n - q_link that moves: excite the joint near "
                     "its resonance, or log a link angle that resolves the deflection");
  }
  if (has("offset")) advice.push_back("the offset and Coulomb friction separate only with motion in both directions");
  return fmt::format("{}", fmt::join(advice, "; "));
}

}  // namespace

JointFitOutput FitJoint(const std::vector<JointLog>& logs, const JointSection& start, const JointFitOptions& options) {
  if (logs.empty()) throw OptionError("no logs given");
  CheckFreeNames(JointParameterTable(), "joint", options.free);
  if (!start.gear_ratio || !(*start.gear_ratio > 0.0)) {
    throw InputError("--params: joint.gear_ratio is needed (q_motor = n theta_m; n = 1 for a direct drive)");
  }
  const double n = *start.gear_ratio;
  const std::vector<std::string> columns = JointColumnNames();
  std::vector<FitParameter> parameters;
  std::map<std::string, double> fixed;
  for (const auto& row : JointParameterTable()) {
    if (row.in_model == nullptr) continue;
    const std::optional<double> value = start.*(row.in_section);
    const bool is_free = std::find(options.free.begin(), options.free.end(), row.spec.key) != options.free.end();
    if (is_free) {
      parameters.push_back({row.spec.key, std::max(row.spec.lower_bound, value.value_or(0.0)), row.spec.lower_bound, 0.0});
    } else if (!value && row.spec.default_free) {
      throw InputError(fmt::format("--params: joint.{} is needed (fixed in this fit)", row.spec.key));
    }
    fixed[row.spec.key] = value.value_or(0.0);
  }

  JointFitOutput out;
  LinearRegression regression(columns);
  for (std::size_t i = 0; i < logs.size(); ++i) {
    const JointLog& log = logs[i];
    if (log.time.size() < kMinAxisLogSamples) {
      throw InputError(fmt::format("{}: {} samples: the joint fit needs at least {}", log.path, log.time.size(),
                                   kMinAxisLogSamples));
    }
    AxisLog motor{log.path, log.time, log.motor_position, {}, {}}, link{log.path, log.time, log.link_position, {}, {}};
    for (double& q : motor.position) q /= n;
    const AxisDerivatives dm = DifferentiateAxisLog(motor, options.cutoff);
    const AxisDerivatives dl = DifferentiateAxisLog(link, options.cutoff);
    // The same zero-phase filter on the angles and the torque as on the rates.
    std::vector<double> theta_m = motor.position, theta_l = link.position, tau = log.torque;
    out.cutoff = dm.rate_hz > 0.0 ? (options.cutoff > 0.0 ? options.cutoff : dm.rate_hz / 40.0) : 0.0;
    if (dm.rate_hz > 0.0) {
      theta_m = ZeroPhaseLowPass(theta_m, out.cutoff, dm.rate_hz);
      theta_l = ZeroPhaseLowPass(theta_l, out.cutoff, dm.rate_hz);
      tau = ZeroPhaseLowPass(tau, out.cutoff, dm.rate_hz);
    }
    // The zero-phase filter's start-up at both ends: two cutoff periods left out.
    const std::size_t edge = dm.rate_hz > 0.0 ? static_cast<std::size_t>(std::ceil(2.0 * dm.rate_hz / out.cutoff)) : 0;
    std::vector<char> valid(log.time.size(), 0);
    for (std::size_t k = edge; k + edge < log.time.size(); ++k) valid[k] = dm.valid[k] && dl.valid[k];
    double max_m = 0.0, max_l = 0.0;
    for (std::size_t k = 0; k < log.time.size(); ++k) {
      if (!valid[k]) continue;
      max_m = std::max(max_m, std::abs(dm.rate[k]));
      max_l = std::max(max_l, std::abs(dl.rate[k]));
    }
    const double floor_m = options.min_rate_fraction * max_m, floor_l = options.min_rate_fraction * max_l;
    // Equation 0 (motor) needs the motor moving, 1 (total) both.
    for (int equation : {0, 1}) {
      regression.BeginChannel(log.path + (equation == 0 ? ":motor" : ":total"));
      for (std::size_t k = 0; k < log.time.size(); ++k) {
        const bool motor_moves = max_m > 0.0 && std::abs(dm.rate[k]) >= floor_m;
        const bool link_moves = max_l > 0.0 && std::abs(dl.rate[k]) >= floor_l;
        if (!valid[k] || !motor_moves || (equation == 1 && !link_moves)) continue;
        const JointRegressors r = CalcJointRegressors(theta_m[k], dm.rate[k], dm.acceleration[k], theta_l[k],
                                                      dl.rate[k], dl.acceleration[k]);
        const auto& row = equation == 0 ? r.motor : r.total;
        regression.AddRow({row.begin(), row.end()}, n * tau[k]);
        out.time.push_back(log.time[k]);
        out.measured.push_back(n * tau[k]);
        out.equation.push_back(equation);
        out.log_index.push_back(static_cast<int>(i));
      }
    }
  }
  if (regression.rows() <= parameters.size()) {
    throw IdentificationError(fmt::format("the logs leave {} usable rows for {} free parameters: the joint does not move",
                                          regression.rows(), parameters.size()));
  }
  FitOptions fit_options = options.fit;
  if (!fit_options.advice) fit_options.advice = JointAdvice;
  out.fit = regression.Fit(parameters, fixed, fit_options);
  std::map<std::string, double> values = fixed;
  for (const auto& e : out.fit.estimates) values[e.name] = e.value;
  out.params = JointParameters{};
  for (const auto& row : JointParameterTable()) {
    if (row.in_model != nullptr) out.params.*(row.in_model) = values[row.spec.key];
  }
  std::vector<std::string> nonnegative;
  for (const auto& row : JointParameterTable()) {
    if (row.in_model != nullptr && row.spec.lower_bound == 0.0) nonnegative.emplace_back(row.spec.key);
  }
  RequireDetermined(out.fit, nonnegative, kMaxRelativeStd, out.fit.warnings);
  out.model = regression.Predict(values);
  return out;
}

}  // namespace driveid
