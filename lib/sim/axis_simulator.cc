#include "sim/axis_simulator.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/errors.h"
#include "sim/cvodes_integrator.h"
#include "sim/held_input_driver.h"

namespace driveid {
namespace {
constexpr int kQ = 0, kV = 1;

int Sign(double value) { return (value > 0.0) - (value < 0.0); }
}  // namespace

class AxisSimulator::System final : public SensitivityOdeSystem, public HeldInputSystem {
 public:
  System(std::vector<int> terms, double position_tolerance, double rate_tolerance) : terms_(std::move(terms)) {
    for (int j : terms_) {
      if (j < 0 || j >= kAxisAllTerms) throw std::logic_error("AxisSimulator: term index out of range");
    }
    IntegratorOptions options;
    options.relative_tolerance = 1e-8;
    options.absolute_tolerance = {position_tolerance, rate_tolerance};
    integrator_ = std::make_unique<CvodesIntegrator>(*this, options);
  }

  int state_size() const override { return 2; }
  int sensitivity_count() const override { return static_cast<int>(terms_.size()); }
  int root_count() const override { return 1; }

  void CalcDerivatives(double, const double* x, double* dx) const override {
    dx[kQ] = x[kV];
    dx[kV] = Acceleration(x);
  }
  void CalcStateJacobian(double, const double* x, double* jacobian) const override {
    double dq = 0.0, dv = 0.0;
    ForceGradient(x, &dq, &dv);
    // Column-major: (row, col) at col * 2 + row.
    jacobian[0] = 0.0;
    jacobian[1] = -dq / theta_[kAxisInertia];
    jacobian[2] = 1.0;
    jacobian[3] = -dv / theta_[kAxisInertia];
  }
  void CalcSensitivityDerivative(double, const double* x, int j, const double* s, double* ds) const override {
    double dq = 0.0, dv = 0.0;
    ForceGradient(x, &dq, &dv);
    const int term = terms_[static_cast<std::size_t>(j)];
    double forcing = 0.0;
    if (term == kAxisInertia) {
      forcing = -Acceleration(x) / theta_[kAxisInertia];
    } else if (term < static_cast<int>(kAxisTerms)) {
      forcing = -Regressors(x)[static_cast<std::size_t>(term)] / theta_[kAxisInertia];
    } else if (StribeckActive()) {
      // d/d tau_s and d/d v_s of tau_s m exp(-(v/v_s)^2).
      const double vs = theta_[kAxisStribeckVelocity], e = StribeckFactor(x[kV]);
      forcing = term == kAxisStribeck ? -mode_ * e / theta_[kAxisInertia]
                                      : -theta_[kAxisStribeck] * mode_ * e * 2.0 * x[kV] * x[kV] / (vs * vs * vs) /
                                            theta_[kAxisInertia];
    }
    ds[kQ] = s[kV];
    ds[kV] = (-dq * s[kQ] - dv * s[kV]) / theta_[kAxisInertia] + forcing;
  }
  void CalcRoots(double, const double* x, double* g) const override { g[0] = x[kV]; }

  void Simulate(const AxisParameters& p, const std::vector<double>& time, const std::vector<double>& torque, double q0,
                double v0, bool with_sensitivities, AxisResponse* out) {
    for (int j = 0; j < kAxisAllTerms; ++j) theta_[static_cast<std::size_t>(j)] = p.*(AxisTermRow(j).in_model);
    if (!(theta_[kAxisInertia] > 0.0)) throw IdentificationError("simulation: the axis needs inertia > 0");
    const std::size_t samples = time.size(), np = terms_.size();
    with_sensitivities = with_sensitivities && np > 0;
    out->position.assign(samples, 0.0);
    out->rate.assign(samples, 0.0);
    out->mode.assign(samples, 0);
    out->position_sensitivity.assign(with_sensitivities ? samples * np : 0, 0.0);
    out->rate_sensitivity.assign(with_sensitivities ? samples * np : 0, 0.0);
    out->switch_count = 0;
    if (samples == 0) return;
    x_[kQ] = q0;
    x_[kV] = v0;
    s_.assign(2 * np, 0.0);
    u_ = torque[0];
    mode_ = Sign(v0);
    if (mode_ == 0) DecideModeAtRest();
    with_sensitivities_ = with_sensitivities;
    out_ = out;
    Record(0);
    out->switch_count = RunHeldInput(*integrator_, time, torque, *this, "axis");
  }

  // HeldInputSystem (sim/held_input_driver.h): stuck, the axis has no dynamics.
  void SetInput(double input) override {
    u_ = input;
    if (x_[kV] == 0.0) DecideModeAtRest();
  }
  bool Frozen() const override { return mode_ == 0; }
  void Restart(double t) override { Restart(t, with_sensitivities_); }
  void HandleSwitch() override { HandleSwitch(with_sensitivities_); }
  void CopyFromIntegrator() override { CopyFromIntegrator(with_sensitivities_); }
  void Record(std::size_t k) override { Record(k, with_sensitivities_, out_); }

 private:
  std::array<double, kAxisTerms> Regressors(const double* x) const {
    return CalcAxisRegressors(x[kQ], x[kV], 0.0, mode_);
  }
  bool StribeckActive() const { return theta_[kAxisStribeck] != 0.0 && theta_[kAxisStribeckVelocity] > 0.0; }
  double StribeckFactor(double v) const {
    const double r = v / theta_[kAxisStribeckVelocity];
    return std::exp(-r * r);
  }
  // J v' = u - F, F the sum of all terms but the inertia.
  double Acceleration(const double* x) const {
    const auto phi = Regressors(x);
    double force = 0.0;
    for (std::size_t j = 1; j < kAxisTerms; ++j) force += theta_[j] * phi[j];
    if (StribeckActive()) force += theta_[kAxisStribeck] * mode_ * StribeckFactor(x[kV]);
    return (u_ - force) / theta_[kAxisInertia];
  }
  void ForceGradient(const double* x, double* dq, double* dv) const {
    *dq = -theta_[kAxisGravityCos] * std::sin(x[kQ]) + theta_[kAxisGravitySin] * std::cos(x[kQ]);
    *dv = theta_[kAxisViscous] + (mode_ > 0 ? theta_[kAxisViscousPos] : 0.0) + (mode_ < 0 ? theta_[kAxisViscousNeg] : 0.0);
    if (StribeckActive()) {
      const double vs = theta_[kAxisStribeckVelocity];
      *dv += theta_[kAxisStribeck] * mode_ * StribeckFactor(x[kV]) * (-2.0 * x[kV] / (vs * vs));
    }
  }
  // v = 0: stuck if friction holds the static torque, else slide towards it.
  void DecideModeAtRest() {
    const double net = u_ - theta_[kAxisOffset] - theta_[kAxisGravityCos] * std::cos(x_[kQ]) - theta_[kAxisGravitySin] * std::sin(x_[kQ]);
    // Breakaway: Coulomb plus the Stribeck excess (its value at v = 0).
    const double excess = StribeckActive() ? theta_[kAxisStribeck] : 0.0;
    const double forward = theta_[kAxisCoulomb] + theta_[kAxisCoulombPos] + excess,
                 backward = theta_[kAxisCoulomb] + theta_[kAxisCoulombNeg] + excess;
    mode_ = net > forward ? 1 : (net < -backward ? -1 : 0);
  }
  void Restart(double t, bool with_sensitivities) {
    pointers_.clear();
    for (std::size_t j = 0; j < terms_.size(); ++j) pointers_.push_back(&s_[2 * j]);
    integrator_->Restart(t, x_.data(), pointers_, with_sensitivities);
  }
  void CopyFromIntegrator(bool with_sensitivities) {
    std::copy(integrator_->state(), integrator_->state() + 2, x_.begin());
    if (!with_sensitivities) return;
    for (std::size_t j = 0; j < terms_.size(); ++j) {
      const double* s = integrator_->sensitivity(static_cast<int>(j));
      s_[2 * j] = s[0];
      s_[2 * j + 1] = s[1];
    }
  }
  // The rate crossed 0 while sliding: stick or reverse, with the jump
  // conditions of the header.
  void HandleSwitch(bool with_sensitivities) {
    CopyFromIntegrator(with_sensitivities);
    x_[kV] = 0.0;
    const double before = Acceleration(x_.data());
    DecideModeAtRest();
    const double after = mode_ == 0 ? 0.0 : Acceleration(x_.data());
    if (!with_sensitivities || before == 0.0) return;
    for (std::size_t j = 0; j < terms_.size(); ++j) {
      const double time_derivative = -s_[2 * j + 1] / before;  // dt*/dp_j
      // q' = v is 0 on both sides: s_q keeps its value.
      s_[2 * j + 1] += (before - after) * time_derivative;
    }
  }
  void Record(std::size_t k, bool with_sensitivities, AxisResponse* out) const {
    out->position[k] = x_[kQ];
    out->rate[k] = x_[kV];
    out->mode[k] = mode_;
    if (!with_sensitivities) return;
    const std::size_t np = terms_.size();
    for (std::size_t j = 0; j < np; ++j) {
      out->position_sensitivity[k * np + j] = s_[2 * j];
      out->rate_sensitivity[k * np + j] = s_[2 * j + 1];
    }
  }

  std::vector<int> terms_;
  std::unique_ptr<CvodesIntegrator> integrator_;
  std::array<double, kAxisAllTerms> theta_{};
  std::array<double, 2> x_{};
  std::vector<double> s_;
  std::vector<const double*> pointers_;
  double u_ = 0.0;
  int mode_ = 0;
  bool with_sensitivities_ = false;
  AxisResponse* out_ = nullptr;
};

AxisSimulator::AxisSimulator(std::vector<int> terms, double position_tolerance, double rate_tolerance)
    : system_(std::make_unique<System>(std::move(terms), position_tolerance, rate_tolerance)) {}

AxisSimulator::~AxisSimulator() = default;

void AxisSimulator::Simulate(const AxisParameters& p, const std::vector<double>& time,
                             const std::vector<double>& torque, double q0, double v0, bool with_sensitivities,
                             AxisResponse* response) {
  system_->Simulate(p, time, torque, q0, v0, with_sensitivities, response);
}

}  // namespace driveid
