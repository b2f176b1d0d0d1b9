#include "sim/joint_simulator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/errors.h"
#include "sim/cvodes_integrator.h"
#include "sim/held_input_driver.h"

namespace driveid {
namespace {
constexpr int kThetaM = 0, kOmegaM = 1, kThetaL = 2, kOmegaL = 3, kStates = 4;
constexpr int kSimulatedTerms = kJointGravitySin + 1;

int Sign(double value) { return (value > 0.0) - (value < 0.0); }
}  // namespace

class JointSimulator::System final : public SensitivityOdeSystem, public HeldInputSystem {
 public:
  System(std::vector<int> terms, double angle_tolerance, double rate_tolerance) : terms_(std::move(terms)) {
    for (int j : terms_) {
      if (j < 0 || j > kJointInitialLinkRate || j == kJointLinkCoulomb) {
        throw std::logic_error("JointSimulator: term not simulated");
      }
    }
    IntegratorOptions options;
    options.relative_tolerance = 1e-8;
    options.absolute_tolerance = {angle_tolerance, rate_tolerance, angle_tolerance, rate_tolerance};
    integrator_ = std::make_unique<CvodesIntegrator>(*this, options);
  }

  int state_size() const override { return kStates; }
  int sensitivity_count() const override { return static_cast<int>(terms_.size()); }
  int root_count() const override { return 2; }

  void CalcDerivatives(double, const double* x, double* dx) const override { Field(x, mode_, dx); }
  void CalcStateJacobian(double, const double* x, double* jacobian) const override {
    // Column-major: (row, col) at col * 4 + row.
    std::fill(jacobian, jacobian + kStates * kStates, 0.0);
    const double k = p_[kJointStiffness], d = p_[kJointDamping], jm = p_[kJointMotorInertia],
                 jl = p_[kJointLinkInertia];
    jacobian[kOmegaM * kStates + kThetaM] = mode_ != 0 ? 1.0 : 0.0;
    if (mode_ != 0) {
      jacobian[kThetaM * kStates + kOmegaM] = -k / jm;
      jacobian[kOmegaM * kStates + kOmegaM] = -(d + p_[kJointMotorViscous]) / jm;
      jacobian[kThetaL * kStates + kOmegaM] = k / jm;
      jacobian[kOmegaL * kStates + kOmegaM] = d / jm;
    }
    jacobian[kOmegaL * kStates + kThetaL] = 1.0;
    jacobian[kThetaM * kStates + kOmegaL] = k / jl;
    jacobian[kOmegaM * kStates + kOmegaL] = d / jl;
    jacobian[kThetaL * kStates + kOmegaL] =
        (-k + p_[kJointGravityCos] * std::sin(x[kThetaL]) - p_[kJointGravitySin] * std::cos(x[kThetaL])) / jl;
    jacobian[kOmegaL * kStates + kOmegaL] = -(d + p_[kJointLinkViscous]) / jl;
  }
  void CalcSensitivityDerivative(double t, const double* x, int j, const double* s, double* ds) const override {
    double a[kStates * kStates];
    CalcStateJacobian(t, x, a);
    for (int row = 0; row < kStates; ++row) {
      double sum = 0.0;
      for (int col = 0; col < kStates; ++col) sum += a[col * kStates + row] * s[col];
      ds[row] = sum;
    }
    // Forcing df/dp_j: motor row (sliding only) and link row.
    const double jm = p_[kJointMotorInertia], jl = p_[kJointLinkInertia];
    const double deflection = x[kThetaM] - x[kThetaL], deflection_rate = x[kOmegaM] - x[kOmegaL];
    double motor = 0.0, link = 0.0;
    switch (terms_[static_cast<std::size_t>(j)]) {
      case kJointMotorInertia: motor = -MotorAcceleration(x, mode_) / jm; break;
      case kJointLinkInertia: link = -LinkAcceleration(x) / jl; break;
      case kJointStiffness: motor = -deflection / jm; link = deflection / jl; break;
      case kJointDamping: motor = -deflection_rate / jm; link = deflection_rate / jl; break;
      case kJointMotorViscous: motor = -x[kOmegaM] / jm; break;
      case kJointMotorCoulomb: motor = -mode_ / jm; break;
      case kJointLinkViscous: link = -x[kOmegaL] / jl; break;
      case kJointOffset: motor = -1.0 / jm; break;
      case kJointGravityCos: link = -std::cos(x[kThetaL]) / jl; break;
      case kJointGravitySin: link = -std::sin(x[kThetaL]) / jl; break;
      default: break;
    }
    if (mode_ != 0) ds[kOmegaM] += motor;
    ds[kOmegaL] += link;
  }
  void CalcRoots(double, const double* x, double* g) const override {
    if (mode_ != 0) {
      g[0] = x[kOmegaM];
      g[1] = 1.0;  // inactive
    } else {
      const double net = StaticTorque(x);
      g[0] = net - p_[kJointMotorCoulomb];
      g[1] = net + p_[kJointMotorCoulomb];
    }
  }

  void Simulate(const JointParameters& p, const std::vector<double>& time, const std::vector<double>& torque,
                const std::array<double, 4>& x0, bool with_sensitivities, JointStateResponse* out) {
    for (int j = 0; j < kSimulatedTerms; ++j) p_[static_cast<std::size_t>(j)] = p.*(JointParameterTable()[j].in_model);
    if (!(p_[kJointMotorInertia] > 0.0) || !(p_[kJointLinkInertia] > 0.0)) {
      throw IdentificationError("simulation: the joint needs both inertias > 0");
    }
    const std::size_t samples = time.size(), np = terms_.size();
    with_sensitivities_ = with_sensitivities && np > 0;
    out->state.assign(samples * kStates, 0.0);
    out->sensitivity.assign(with_sensitivities_ ? samples * np * kStates : 0, 0.0);
    out->mode.assign(samples, 0);
    out->switch_count = 0;
    if (samples == 0) return;
    std::copy(x0.begin(), x0.end(), x_.begin());
    s_.assign(kStates * np, 0.0);
    u_ = torque[0];
    mode_ = Sign(x_[kOmegaM]);
    if (mode_ == 0) DecideModeAtRest();
    for (std::size_t j = 0; j < np; ++j) {
      const int i = InitialStateIndex(terms_[j]);
      // (a stuck motor's rate is held at 0: no sensitivity to its start value)
      if (i >= 0 && !(mode_ == 0 && i == kOmegaM)) s_[kStates * j + static_cast<std::size_t>(i)] = 1.0;
    }
    out_ = out;
    Record(0);
    out->switch_count = RunHeldInput(*integrator_, time, torque, *this, "joint");
  }

  // HeldInputSystem (sim/held_input_driver.h): the link moves even while the
  // motor sticks, so the joint is never frozen.
  void SetInput(double input) override {
    u_ = input;
    if (x_[kOmegaM] == 0.0) DecideModeAtRest();
  }
  bool Frozen() const override { return false; }
  void Restart(double t) override {
    pointers_.clear();
    for (std::size_t j = 0; j < terms_.size(); ++j) pointers_.push_back(&s_[kStates * j]);
    integrator_->Restart(t, x_.data(), pointers_, with_sensitivities_);
  }
  void HandleSwitch() override {
    CopyFromIntegrator();
    if (mode_ != 0) {
      double before[kStates], after[kStates];
      Field(x_.data(), mode_, before);
      x_[kOmegaM] = 0.0;
      DecideModeAtRest();
      Field(x_.data(), mode_, after);
      if (!with_sensitivities_ || before[kOmegaM] == 0.0) return;
      for (std::size_t j = 0; j < terms_.size(); ++j) {
        double* s = &s_[kStates * j];
        const double time_derivative = -s[kOmegaM] / before[kOmegaM];  // dt*/dp_j
        for (int i = 0; i < kStates; ++i) s[i] += (before[i] - after[i]) * time_derivative;
        if (mode_ == 0) s[kOmegaM] = 0.0;
      }
    } else {
      const auto& fired = integrator_->root_directions();
      mode_ = fired[0] != 0 ? 1 : (fired[1] != 0 ? -1 : Sign(StaticTorque(x_.data())));
    }
  }
  void CopyFromIntegrator() override {
    std::copy(integrator_->state(), integrator_->state() + kStates, x_.begin());
    if (!with_sensitivities_) return;
    for (std::size_t j = 0; j < terms_.size(); ++j) {
      const double* s = integrator_->sensitivity(static_cast<int>(j));
      std::copy(s, s + kStates, s_.begin() + static_cast<std::ptrdiff_t>(kStates * j));
    }
  }
  void Record(std::size_t k) override {
    std::copy(x_.begin(), x_.end(), out_->state.begin() + static_cast<std::ptrdiff_t>(k * kStates));
    out_->mode[k] = mode_;
    if (!with_sensitivities_) return;
    std::copy(s_.begin(), s_.end(), out_->sensitivity.begin() + static_cast<std::ptrdiff_t>(k * s_.size()));
  }

 private:
  double StaticTorque(const double* x) const {
    return u_ - p_[kJointStiffness] * (x[kThetaM] - x[kThetaL]) + p_[kJointDamping] * x[kOmegaL] - p_[kJointOffset];
  }
  double MotorAcceleration(const double* x, int mode) const {
    if (mode == 0) return 0.0;
    const double spring = p_[kJointStiffness] * (x[kThetaM] - x[kThetaL]) + p_[kJointDamping] * (x[kOmegaM] - x[kOmegaL]);
    return (u_ - spring - p_[kJointMotorViscous] * x[kOmegaM] - p_[kJointMotorCoulomb] * mode - p_[kJointOffset]) /
           p_[kJointMotorInertia];
  }
  double LinkAcceleration(const double* x) const {
    const double spring = p_[kJointStiffness] * (x[kThetaM] - x[kThetaL]) + p_[kJointDamping] * (x[kOmegaM] - x[kOmegaL]);
    return (spring - p_[kJointLinkViscous] * x[kOmegaL] - p_[kJointGravityCos] * std::cos(x[kThetaL]) -
            p_[kJointGravitySin] * std::sin(x[kThetaL])) /
           p_[kJointLinkInertia];
  }
  void Field(const double* x, int mode, double* dx) const {
    dx[kThetaM] = mode != 0 ? x[kOmegaM] : 0.0;
    dx[kOmegaM] = MotorAcceleration(x, mode);
    dx[kThetaL] = x[kOmegaL];
    dx[kOmegaL] = LinkAcceleration(x);
  }
  // omega_m = 0: stuck if the friction holds the static torque, else slide towards it.
  void DecideModeAtRest() {
    const double net = StaticTorque(x_.data());
    mode_ = std::abs(net) <= p_[kJointMotorCoulomb] ? 0 : Sign(net);
  }

  std::vector<int> terms_;
  std::unique_ptr<CvodesIntegrator> integrator_;
  std::array<double, kSimulatedTerms> p_{};
  std::array<double, kStates> x_{};
  std::vector<double> s_;  // sensitivities, parameter-major
  std::vector<const double*> pointers_;
  double u_ = 0.0;
  int mode_ = 0;
  bool with_sensitivities_ = false;
  JointStateResponse* out_ = nullptr;
};

JointSimulator::JointSimulator(std::vector<int> terms, double angle_tolerance, double rate_tolerance)
    : system_(std::make_unique<System>(terms, angle_tolerance, rate_tolerance)),
      exact_(std::make_unique<JointExactSimulator>(terms)), terms_(terms) {}

JointSimulator::~JointSimulator() = default;

void JointSimulator::Simulate(const JointParameters& p, const std::vector<double>& time,
                              const std::vector<double>& motor_torque, const std::array<double, 4>& x0,
                              bool with_sensitivities, JointStateResponse* response) {
  const bool gravity = p.gravity_cos != 0.0 || p.gravity_sin != 0.0 ||
                       std::any_of(terms_.begin(), terms_.end(),
                                   [](int j) { return j == kJointGravityCos || j == kJointGravitySin; });
  if (gravity || use_integrator_) {
    system_->Simulate(p, time, motor_torque, x0, with_sensitivities, response);
  } else {
    exact_->Simulate(p, time, motor_torque, x0, with_sensitivities, response);
  }
}

}  // namespace driveid
