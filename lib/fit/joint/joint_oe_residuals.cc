#include "fit/joint/joint_oe_residuals.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <fmt/format.h>

#include "core/errors.h"
#include "fit/axis/axis_rows.h"
#include "fit/core/fit_statistics.h"
#include "models/missing_values.h"
#include "sim/joint_simulator.h"

namespace driveid {
namespace joint_oe {
namespace {

class JointOeResiduals final : public Residuals {
 public:
  JointOeResiduals(std::vector<OeLog>& logs, const JointParameters& fixed, std::vector<int> terms, int columns,
                   double gear_ratio, double angle_tolerance, double rate_tolerance)
      : logs_(logs), params_(fixed), terms_(terms), columns_(columns), n_(gear_ratio),
        simulator_(SimulatedTerms(std::move(terms)), angle_tolerance, rate_tolerance) {
    for (auto& l : logs_) {
      for (auto& c : l.channels) {
        c.first_row = rows_;
        rows_ += static_cast<int>(l.log->time.size());
      }
    }
    for (std::size_t j = 0; j < terms_.size(); ++j) {
      if (terms_[j] == kJointStiffness) stiffness_ = static_cast<int>(j);
      if (terms_[j] == kJointDamping) damping_ = static_cast<int>(j);
    }
  }
  int residual_count() const override { return rows_; }

  bool Evaluate(const double* parameters, double* residuals, double* jacobian) override {
    Set(parameters);
    try {
      for (const auto& l : logs_) {
        for (const auto& shot : l.shots) {
          simulator_.Simulate(params_, shot.segment.time, shot.segment.torque, Start(shot, parameters),
                              jacobian != nullptr, &response_);
          for (const auto& c : l.channels) Fill(l, shot, c, parameters, residuals, jacobian);
        }
      }
    } catch (const IdentificationError& e) {
      last_failure_ = e.what();
      return false;
    }
    for (int i = 0; i < rows_; ++i) {
      if (!std::isfinite(residuals[i])) {
        last_failure_ = "the simulated joint is not finite";
        return false;
      }
    }
    last_failure_.clear();
    return true;
  }
  std::string LastFailure() const override { return last_failure_; }

  /// Log i simulated whole (log units) at `parameters`, from its first
  /// segment's start state.
  void SimulateWhole(const double* parameters, std::size_t i, std::vector<double>* motor, std::vector<double>* link) override {
    Set(parameters);
    const OeLog& l = logs_[i];
    simulator_.Simulate(params_, l.log->time, l.torque, Start(l.shots.front(), parameters), false, &response_);
    motor->resize(l.log->time.size());
    link->resize(l.log->time.size());
    StoreAngles(0, l.log->time.size(), motor, link);
  }

  /// The simulated angles of log i (log units) at `parameters`.
  void SimulateAngles(const double* parameters, std::size_t i, std::vector<double>* motor, std::vector<double>* link) override {
    Set(parameters);
    const OeLog& l = logs_[i];
    motor->resize(l.log->time.size());
    link->resize(l.log->time.size());
    for (const auto& shot : l.shots) {
      simulator_.Simulate(params_, shot.segment.time, shot.segment.torque, Start(shot, parameters), false,
                          &response_);
      StoreAngles(shot.segment.begin, shot.segment.time.size(), motor, link);
    }
  }

 private:
  // The last simulation's `count` angles (log units) into samples from `begin`.
  void StoreAngles(std::size_t begin, std::size_t count, std::vector<double>* motor, std::vector<double>* link) const {
    for (std::size_t k = 0; k < count; ++k) {
      (*motor)[begin + k] = n_ * response_.state[4 * k];
      (*link)[begin + k] = response_.state[4 * k + 2];
    }
  }

  void Set(const double* parameters) {
    for (std::size_t j = 0; j < terms_.size(); ++j) params_.*(JointParameterTable()[terms_[j]].in_model) = parameters[j];
  }
  static std::array<double, 4> Start(const OeShot& shot, const double* parameters) {
    std::array<double, 4> x0 = shot.segment.x0;
    for (std::size_t i = 0; i < 4; ++i) {
      if (shot.start_parameter[i] >= 0) x0[i] = parameters[shot.start_parameter[i]];
    }
    return x0;
  }

  // Model value of a channel from the state x and its derivative from the
  // state sensitivity s (d x / d p).
  double Value(Channel kind, const double* x, double offset) const {
    switch (kind) {
      case Channel::kMotorAngle: return n_ * x[0];
      case Channel::kMotorRate: return n_ * x[1];
      case Channel::kLinkAngle: return x[2];
      case Channel::kLinkRate: return x[3];
      case Channel::kShaftTorque:
        return params_.stiffness * (x[0] - x[2]) + params_.damping * (x[1] - x[3]) + offset;
    }
    return 0.0;
  }

  void Fill(const OeLog& l, const OeShot& shot, const OeChannel& c, const double* parameters, double* residuals,
            double* jacobian) const {
    const std::size_t samples = shot.segment.time.size(), p = terms_.size();
    const std::size_t columns = static_cast<std::size_t>(columns_), begin = shot.segment.begin;
    const std::size_t simulated = p + 4;  // sensitivities per sample: the terms, then x(t_0)
    const double offset = l.offset_parameter >= 0 ? parameters[l.offset_parameter] : params_.link_torque_offset;
    const std::vector<double>& measured = *c.measured;
    for (std::size_t k = 0; k < samples; ++k) {
      const double* x = &response_.state[4 * k];
      const std::size_t row = static_cast<std::size_t>(c.first_row) + begin + k;
      residuals[row] = c.weight * (Value(c.kind, x, offset) - measured[begin + k]);
      if (jacobian == nullptr) continue;
      double* out = jacobian + row * columns;
      std::fill(out, out + columns, 0.0);
      for (std::size_t i = 0; i < 4; ++i) {
        if (shot.start_parameter[i] < 0) continue;
        out[shot.start_parameter[i]] =
            c.weight * Value(c.kind, &response_.sensitivity[(k * simulated + p + i) * 4], 0.0);
      }
      for (std::size_t j = 0; j < p; ++j) {
        const double* s = &response_.sensitivity[(k * simulated + j) * 4];
        double d = Value(c.kind, s, 0.0);  // linear in the state (tau_link: at fixed k, d)
        if (c.kind == Channel::kShaftTorque) {
          if (static_cast<int>(j) == stiffness_) d += x[0] - x[2];
          if (static_cast<int>(j) == damping_) d += x[1] - x[3];
        }
        out[j] = c.weight * d;
      }
      if (c.kind == Channel::kShaftTorque && l.offset_parameter >= 0) out[l.offset_parameter] = c.weight;
    }
  }

  std::vector<OeLog>& logs_;
  JointParameters params_;
  std::vector<int> terms_;
  int columns_ = 0;  // parameters: the terms, the logs' tau_l0, the logs' x(t_0)
  double n_ = 1.0;
  int stiffness_ = -1, damping_ = -1;
  JointSimulator simulator_;
  JointStateResponse response_;
  int rows_ = 0;
  std::string last_failure_;
};

}  // namespace

// The simulator's terms: the fit's free joint terms, then the initial state.
std::vector<int> SimulatedTerms(std::vector<int> terms) {
  for (int t : {kJointInitialMotorAngle, kJointInitialMotorRate, kJointInitialLinkAngle, kJointInitialLinkRate}) {
    terms.push_back(t);
  }
  return terms;
}

// The logs' channels, start states and first-pass weights.
std::vector<OeLog> PrepareLogs(const std::vector<JointLog>& logs, double n) {
  std::vector<OeLog> oe(logs.size());
  for (std::size_t i = 0; i < logs.size(); ++i) {
    const JointLog& log = logs[i];
    if (log.time.size() < kMinAxisLogSamples) {
      throw InputError(fmt::format("{}: {} samples: the joint fit needs at least {}", log.path, log.time.size(),
                                   kMinAxisLogSamples));
    }
    if (log.torque.empty()) {
      throw InputError(fmt::format("{}: ‹method› oe simulates the joint from the motor torque tau (or i), which the "
                                   "log lacks: use ‹method› id",
                                   log.path));
    }
    OeLog& l = oe[i];
    l.log = &log;
    for (double tau : log.torque) l.torque.push_back(n * tau);
    const auto add = [&](Channel kind, const std::vector<double>& measured, const char* name) {
      if (measured.empty()) return;
      const double spread = CalcRmsDeviation(measured);
      if (!(spread > 0.0)) {
        if (kind == Channel::kMotorAngle || kind == Channel::kLinkAngle) {
          throw IdentificationError(fmt::format("{}: {} never changes: output error has nothing to fit", log.path, name));
        }
        return;
      }
      l.channels.push_back({kind, &measured, 1.0 / spread, 0, {}, fmt::format("{}:{}", log.path, name)});
    };
    add(Channel::kMotorAngle, log.motor_position, "q_motor");
    add(Channel::kLinkAngle, log.link_position, "q_link");
    add(Channel::kMotorRate, log.motor_rate, "qd_motor");
    add(Channel::kLinkRate, log.link_rate, "qd_link");
    add(Channel::kShaftTorque, log.link_torque, "tau_link");
  }
  return oe;
}

void SetWeighted(std::vector<OeLog>& oe, std::vector<FitChannel>* channels) {
  channels->clear();
  for (auto& l : oe) {
    for (auto& c : l.channels) {
      c.weighted.clear();
      for (double v : *c.measured) c.weighted.push_back(v * c.weight);
      channels->push_back({c.name, c.first_row, static_cast<int>(c.weighted.size()), c.weighted.data()});
    }
  }
}

// Integrator tolerances: the angles resolve the smallest measured deflection
// spread by 1e-6, the rates the same over 1 ms.
std::array<double, 2> Tolerances(const std::vector<JointLog>& logs, double n) {
  double deflection = HUGE_VAL;
  for (const auto& log : logs) {
    std::vector<double> d(log.time.size());
    for (std::size_t k = 0; k < d.size(); ++k) d[k] = log.motor_position[k] / n - log.link_position[k];
    const double spread = CalcRmsDeviation(d);
    if (spread > 0.0) deflection = std::min(deflection, spread);
  }
  if (!std::isfinite(deflection)) deflection = 1e-6;
  const double angle = std::max(1e-6 * deflection, 1e-14);
  return {angle, 1e3 * angle};
}

std::unique_ptr<Residuals> MakeResiduals(std::vector<OeLog>& logs, const JointParameters& fixed, std::vector<int> terms,
                                         int columns, double gear_ratio, double angle_tolerance,
                                         double rate_tolerance) {
  return std::make_unique<JointOeResiduals>(logs, fixed, std::move(terms), columns, gear_ratio, angle_tolerance,
                                            rate_tolerance);
}

}  // namespace joint_oe
}  // namespace driveid
