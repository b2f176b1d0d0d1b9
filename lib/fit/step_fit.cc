#include "fit/step_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <tuple>

#include <fmt/format.h>

#include "core/errors.h"
#include "io/csv_log.h"
#include "sim/drivetrain_simulator.h"

namespace driveid {
namespace {

const DriveTrainParameter kAllParameters[] = {
    DriveTrainParameter::kViscousFriction, DriveTrainParameter::kMotorInertia,
    DriveTrainParameter::kGearboxInertia,  DriveTrainParameter::kLinkStiffness,
    DriveTrainParameter::kGearboxStiffness, DriveTrainParameter::kCoulombFriction};

bool Contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

// Model-specific advice for a non-identifiable set (docs/models.md#drive-train identifiability).
std::string StepAdvice(const std::vector<std::string>& involved) {
  std::vector<std::string> advice;
  const auto key = [](DriveTrainParameter parameter) { return std::string(DriveTrainParameterKey(parameter)); };
  const bool link = Contains(involved, key(DriveTrainParameter::kLinkStiffness));
  const bool gearbox = Contains(involved, key(DriveTrainParameter::kGearboxStiffness));
  if (link && gearbox) {
    advice.push_back("fix k_Tl or k_Tg with --params: only their series combination enters the strain gauge's step "
                     "response; a logged link angle q_link separates them (docs/models.md#drive-train)");
  } else if ((link || gearbox) && (Contains(involved, key(DriveTrainParameter::kMotorInertia)) ||
                                    Contains(involved, key(DriveTrainParameter::kViscousFriction)))) {
    advice.push_back("a step response fixes only Theta_motor/k_eq and d_g/k_eq: fix the stiffness with --params");
  }
  if (Contains(involved, "offset") || Contains(involved, "offset_1")) {
    advice.push_back("a per-log offset needs samples before the step to separate it from tau_c");
  }
  return fmt::format("{}", fmt::join(advice, "; "));
}

// The residual channels of one log: the strain gauge, then (when logged and
// used) the motor encoder q_motor = n_g phi and the link angle q_link = Delta,
// each angle weighted by RMS(tau_link) / RMS(angle) so that all count alike
// and tau_link keeps its unit.
struct StepChannels {
  int first_row = 0;
  double motor_weight = 0.0, link_weight = 0.0;  // 0: channel not used
  std::vector<double> weighted_motor, weighted_link;
};

class StepResiduals final : public ResidualModel {
 public:
  StepResiduals(const std::vector<StepLog>& logs, const DriveTrainParameters& start, DriveTrainModel model,
                std::vector<DriveTrainParameter> ode_parameters, bool fit_offsets, bool use_angles)
      : logs_(logs), params_(start), ode_parameters_(ode_parameters), fit_offsets_(fit_offsets),
        simulator_(model, start, std::move(ode_parameters)) {
    for (const auto& log : logs_) {
      StepChannels c;
      c.first_row = rows_;
      const int n = static_cast<int>(log.time.size());
      rows_ += n;
      const double torque_scale = CalcRmsDeviation(log.link_torque);
      // An angle channel is used when asked for, logged and moving.
      const auto weigh = [&](const std::vector<double>& angle, double* weight, std::vector<double>* weighted) {
        const double angle_scale = use_angles ? CalcRmsDeviation(angle) : 0.0;
        if (!(angle_scale > 0.0 && torque_scale > 0.0)) return;
        *weight = torque_scale / angle_scale;
        for (double q : angle) weighted->push_back(q * *weight);
        rows_ += n;
      };
      weigh(log.motor_angle, &c.motor_weight, &c.weighted_motor);
      weigh(log.link_angle, &c.link_weight, &c.weighted_link);
      channels_.push_back(std::move(c));
    }
  }

  int residual_count() const override { return rows_; }
  int parameter_count() const {
    return static_cast<int>(ode_parameters_.size()) + (fit_offsets_ ? static_cast<int>(logs_.size()) : 0);
  }

  bool Evaluate(const double* parameters, double* residuals, double* jacobian) override {
    const std::size_t q = ode_parameters_.size();
    const std::size_t p = static_cast<std::size_t>(parameter_count());
    for (std::size_t j = 0; j < q; ++j) SetDriveTrainParameter(params_, ode_parameters_[j], parameters[j]);
    try {
      for (std::size_t i = 0; i < logs_.size(); ++i) {
        const StepLog& log = logs_[i];
        const StepChannels& c = channels_[i];
        simulator_.Simulate(params_, log.time, log.motor_torque, jacobian != nullptr, &response_);
        const double offset = fit_offsets_ ? parameters[q + i] : 0.0;
        const std::size_t n = log.time.size();
        std::size_t base = static_cast<std::size_t>(c.first_row);
        for (std::size_t k = 0; k < n; ++k) {
          residuals[base + k] = response_.link_torque[k] + offset - log.link_torque[k];
          if (jacobian == nullptr) continue;
          double* row = jacobian + (base + k) * p;
          for (std::size_t j = 0; j < q; ++j) row[j] = response_.link_torque_sensitivity[k * q + j];
          for (std::size_t m = q; m < p; ++m) row[m] = (fit_offsets_ && m - q == i) ? 1.0 : 0.0;
        }
        // Angle channels: q_motor = n_g phi, q_link = Delta (no strain-gauge offset).
        const double n_g = params_.gear_ratio;
        for (const auto& [weight, measured, model, sensitivity, scale] :
             {std::tuple{c.motor_weight, &log.motor_angle, &response_.motor_angle,
                         &response_.motor_angle_sensitivity, n_g},
              std::tuple{c.link_weight, &log.link_angle, &response_.deflection, &response_.deflection_sensitivity,
                         1.0}}) {
          if (weight == 0.0) continue;
          base += n;
          for (std::size_t k = 0; k < n; ++k) {
            residuals[base + k] = weight * (scale * (*model)[k] - (*measured)[k]);
            if (jacobian == nullptr) continue;
            double* row = jacobian + (base + k) * p;
            for (std::size_t j = 0; j < q; ++j) row[j] = weight * scale * (*sensitivity)[k * q + j];
            for (std::size_t m = q; m < p; ++m) row[m] = 0.0;
          }
        }
      }
    } catch (const IdentificationError& e) {
      last_failure_ = e.what();
      return false;  // integrator failure at these values: the solver backs off
    }
    for (int i = 0; i < rows_; ++i) {
      if (!std::isfinite(residuals[i])) {
        last_failure_ = "the simulated response is not finite";
        return false;
      }
    }
    last_failure_.clear();
    return true;
  }

  std::string LastFailure() const override { return last_failure_; }

  std::vector<double> Simulate(std::size_t i, const double* parameters) {
    const std::size_t q = ode_parameters_.size();
    for (std::size_t j = 0; j < q; ++j) SetDriveTrainParameter(params_, ode_parameters_[j], parameters[j]);
    simulator_.Simulate(params_, logs_[i].time, logs_[i].motor_torque, false, &response_);
    std::vector<double> out = response_.link_torque;
    if (fit_offsets_) {
      for (double& y : out) y += parameters[q + i];
    }
    return out;
  }

  /// The fit's channels: per log tau_link, then q_motor and q_link where used.
  std::vector<FitChannel> Channels() const {
    std::vector<FitChannel> out;
    for (std::size_t i = 0; i < logs_.size(); ++i) {
      const StepChannels& c = channels_[i];
      const int n = static_cast<int>(logs_[i].time.size());
      int begin = c.first_row;
      out.push_back({logs_[i].path + ":tau_link", begin, n, logs_[i].link_torque.data()});
      if (c.motor_weight > 0.0) out.push_back({logs_[i].path + ":q_motor", begin += n, n, c.weighted_motor.data()});
      if (c.link_weight > 0.0) out.push_back({logs_[i].path + ":q_link", begin += n, n, c.weighted_link.data()});
    }
    return out;
  }
  /// RMSE back in the angle channels' units.
  void UnweightRmse(FitResult& fit) const {
    std::size_t index = 0;
    for (const auto& c : channels_) {
      ++index;
      if (c.motor_weight > 0.0) fit.channels[index++].rmse /= c.motor_weight;
      if (c.link_weight > 0.0) fit.channels[index++].rmse /= c.link_weight;
    }
  }

 private:
  const std::vector<StepLog>& logs_;
  DriveTrainParameters params_;
  std::vector<DriveTrainParameter> ode_parameters_;
  bool fit_offsets_;
  DriveTrainSimulator simulator_;
  DriveTrainResponse response_;
  std::vector<StepChannels> channels_;
  int rows_ = 0;
  std::string last_failure_;
};

void CheckStepLog(const StepLog& log) {
  if (log.time.size() < kMinStepLogSamples) {
    throw InputError(fmt::format("{}: {} samples: a step log needs at least {}", log.path, log.time.size(),
                                 kMinStepLogSamples));
  }
  const bool steps = std::any_of(log.motor_torque.begin(), log.motor_torque.end(),
                                 [&](double u) { return u != log.motor_torque.front(); });
  if (!steps && log.motor_torque.front() == 0.0) {
    throw IdentificationError(fmt::format(
        "{}: column 'tau_motor' is zero throughout: the log holds no torque step to identify anything from",
        log.path));
  }
}

}  // namespace

std::unique_ptr<ResidualModel> MakeStepResiduals(const std::vector<StepLog>& logs, const DriveTrainParameters& start,
                                                 DriveTrainModel model, std::vector<DriveTrainParameter> free,
                                                 bool fit_offsets) {
  return std::make_unique<StepResiduals>(logs, start, model, std::move(free), fit_offsets, false);
}



StepFitOutput FitStepResponses(const std::vector<StepLog>& logs, const DriveTrainParameters& start,
                               const StepFitOptions& options) {
  if (logs.empty()) throw OptionError("no step logs given");
  CheckFreeNames(DriveTrainParameterTable(), "step", options.free, {"offset"});
  for (const auto& log : logs) CheckStepLog(log);
  if (options.model == DriveTrainModel::kFull && !(start.gearbox_inertia > 0.0)) {
    throw InputError("the full model needs drivetrain.Theta_g > 0 in --params");
  }
  if (options.model == DriveTrainModel::kReduced &&
      Contains(options.free, DriveTrainParameterKey(DriveTrainParameter::kGearboxInertia))) {
    throw IdentificationError("Theta_g has no effect in the reduced model (it sets Theta_g = 0): use --model full");
  }

  std::vector<DriveTrainParameter> ode_parameters;
  std::vector<FitParameter> fit_parameters;
  for (auto parameter : kAllParameters) {
    const std::string key = DriveTrainParameterKey(parameter);
    if (!Contains(options.free, key)) continue;
    const double value = GetDriveTrainParameter(start, parameter);
    if (!(value > 0.0)) {
      throw InputError(fmt::format("--free {}: the starting value in --params must be > 0, got {}", key, value));
    }
    ode_parameters.push_back(parameter);
    // Friction may vanish; inertias and stiffnesses must stay strictly positive.
    const bool may_vanish = parameter == DriveTrainParameter::kViscousFriction ||
                            parameter == DriveTrainParameter::kCoulombFriction;
    fit_parameters.push_back({key, value, may_vanish ? 0.0 : 1e-6 * value, 0.0});
  }
  const bool fit_offsets = Contains(options.free, "offset");
  if (fit_offsets) {
    double scale = 0.0;
    for (const auto& log : logs) {
      for (double y : log.link_torque) scale = std::max(scale, std::abs(y));
    }
    for (std::size_t i = 0; i < logs.size(); ++i) {
      fit_parameters.push_back({fmt::format("offset_{}", i + 1), 0.0, -std::numeric_limits<double>::infinity(),
                                std::max(1e-3 * scale, 1e-9)});
    }
  }

  StepResiduals residuals(logs, start, options.model, ode_parameters, fit_offsets, true);
  const std::vector<FitChannel> channels = residuals.Channels();
  FitOptions fit_options = options.fit;
  if (!fit_options.advice) fit_options.advice = StepAdvice;

  StepFitOutput output;
  output.fit = FitLeastSquares(residuals, fit_parameters, channels, fit_options);
  residuals.UnweightRmse(output.fit);
  std::vector<double> estimate;
  for (const auto& e : output.fit.estimates) estimate.push_back(e.value);
  output.params = start;
  for (std::size_t j = 0; j < ode_parameters.size(); ++j) SetDriveTrainParameter(output.params, ode_parameters[j], estimate[j]);
  output.offsets.assign(logs.size(), 0.0);
  for (std::size_t i = 0; i < logs.size(); ++i) {
    if (fit_offsets) output.offsets[i] = estimate[ode_parameters.size() + i];
    output.simulated.push_back(residuals.Simulate(i, estimate.data()));
  }
  return output;
}

}  // namespace driveid
