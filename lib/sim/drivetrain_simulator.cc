#include "sim/drivetrain_simulator.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/errors.h"
#include "sim/cvodes_integrator.h"
#include "sim/held_input_driver.h"
#include "sim/switched_linear_exact.h"

namespace driveid {
namespace {
constexpr int kOmega = DriveTrainState::kMotorRate;
static_assert(kOmega == SwitchedLinearExact::kRate, "the exact simulation's rate with friction is the motor's");
constexpr long kSwitchesPerSample = 4, kSwitchBudgetConstant = 2000;

int Sign(double value) { return (value > 0.0) - (value < 0.0); }

// The drive train as the exact simulation's model: its fields are affine in
// the state and the torque within a mode, so A, c, b and their parameter
// derivatives are read off the model's own functions (models/drivetrain.h)
// at the origin and the unit vectors; the reduced model's two states are
// the first two of four (the last two stay 0).
class DriveTrainLinearModel final : public SwitchedLinearModel {
 public:
  DriveTrainLinearModel(DriveTrainModel model, const DriveTrainParameters& params,
                        const std::vector<DriveTrainParameter>& parameters)
      : model_(model), params_(params), parameters_(parameters), n_(DriveTrainStateSize(model)) {}

  ModeField Field(int mode) const override {
    return Affine([&](const double* x, double u, double* dx) {
      CalcDriveTrainDerivatives(params_, model_, u, mode, x, dx);
    });
  }
  ModeField FieldDerivative(int mode, int j) const override {
    const DriveTrainParameter parameter = parameters_[static_cast<std::size_t>(j)];
    return Affine([&](const double* x, double u, double* dx) {
      CalcDriveTrainParameterJacobian(params_, model_, u, mode, x, parameter, dx);
    });
  }
  int InitialStateIndex(int) const override { return -1; }  // the drive starts at rest
  double StaticTorque(const Eigen::Vector4d& x, double u) const override {
    return CalcNetTorque(params_, model_, u, x.data());
  }
  double StaticTorqueRate(const Eigen::Vector4d& dx) const override {
    return CalcNetTorque(params_, model_, 0.0, dx.data());  // (linear in the state without torque)
  }
  double Coulomb() const override { return params_.coulomb_friction; }

 private:
  // The affine map f(x, u) = A x + c + b u of n states, embedded in four.
  template <typename Map>
  ModeField Affine(const Map& f) const {
    ModeField field;
    double x[4] = {0.0, 0.0, 0.0, 0.0}, base[4] = {0.0, 0.0, 0.0, 0.0}, value[4] = {0.0, 0.0, 0.0, 0.0};
    f(x, 0.0, base);
    for (int i = 0; i < n_; ++i) field.c(i) = base[i];
    f(x, 1.0, value);
    for (int i = 0; i < n_; ++i) field.b(i) = value[i] - base[i];
    for (int col = 0; col < n_; ++col) {
      x[col] = 1.0;
      f(x, 0.0, value);
      for (int i = 0; i < n_; ++i) field.a(i, col) = value[i] - base[i];
      x[col] = 0.0;
    }
    return field;
  }

  DriveTrainModel model_;
  const DriveTrainParameters& params_;
  const std::vector<DriveTrainParameter>& parameters_;
  int n_;
};
}  // namespace

class DriveTrainSimulator::System final : public SensitivityOdeSystem, public HeldInputSystem {
 public:
  System(DriveTrainModel model, const DriveTrainParameters& nominal, std::vector<DriveTrainParameter> parameters,
         const SimulationTolerances& tolerances)
      : model_(model), params_(nominal), parameters_(std::move(parameters)),
        n_(DriveTrainStateSize(model)) {
    IntegratorOptions options;
    // Absolute tolerances of the states from the link-torque tolerance; the
    // rates get the same with a time scale of 1 ms.
    const double torque_tolerance = tolerances.link_torque;
    const double phi_tolerance = torque_tolerance / CalcSeriesStiffness(nominal);
    options.relative_tolerance = tolerances.relative;
    options.absolute_tolerance = {phi_tolerance, phi_tolerance * 1e3};
    if (model == DriveTrainModel::kFull) {
      const double deflection_tolerance = torque_tolerance / nominal.link_stiffness;
      options.absolute_tolerance.push_back(deflection_tolerance);
      options.absolute_tolerance.push_back(deflection_tolerance * 1e3);
    }
    for (auto parameter : parameters_) {
      options.parameter_scale.push_back(std::abs(GetDriveTrainParameter(nominal, parameter)));
    }
    integrator_ = std::make_unique<CvodesIntegrator>(*this, options);
    jacobian_.resize(static_cast<std::size_t>(n_ * n_));
  }

  int state_size() const override { return n_; }
  int sensitivity_count() const override { return static_cast<int>(parameters_.size()); }
  int root_count() const override { return 2; }

  void CalcDerivatives(double, const double* x, double* dx) const override {
    CalcDriveTrainDerivatives(params_, model_, motor_torque_, mode_, x, dx);
  }
  void CalcStateJacobian(double, const double*, double* jacobian) const override {
    CalcDriveTrainStateJacobian(params_, model_, mode_, jacobian);
  }
  void CalcSensitivityDerivative(double, const double* x, int j, const double* s, double* ds) const override {
    CalcDriveTrainParameterJacobian(params_, model_, motor_torque_, mode_, x, parameters_[static_cast<std::size_t>(j)], ds);
    for (int col = 0; col < n_; ++col) {
      const double sc = s[col];
      if (sc == 0.0) continue;
      for (int row = 0; row < n_; ++row) ds[row] += jacobian_cache(col, row) * sc;
    }
  }
  void CalcRoots(double, const double* x, double* g) const override {
    if (mode_ != 0) {
      g[0] = x[kOmega];
      g[1] = 1.0;  // inactive
    } else {
      const double net = CalcNetTorque(params_, model_, motor_torque_, x);
      g[0] = net - params_.coulomb_friction;
      g[1] = net + params_.coulomb_friction;
    }
  }

  void set_record_angles(bool record) { record_angles_ = record; }

  void Start(const DriveTrainParameters& params, const std::vector<double>& time,
             const std::vector<double>& motor_torque, bool with_sensitivities) {
    params_ = params;
    with_sensitivities_ = with_sensitivities && !parameters_.empty();
    run_.reset();
    samples_ = time.size();
    next_ = 0;
    if (samples_ == 0) return;
    x_.assign(static_cast<std::size_t>(n_), 0.0);
    s_.assign(parameters_.size() * static_cast<std::size_t>(n_), 0.0);
    mode_ = 0;
    motor_torque_ = motor_torque[0];
    DecideModeAtRest();
    exact_ = integration_ == DriveTrainIntegration::kExact;
    if (exact_) {
      time_ = &time;
      torque_ = &motor_torque;
      exact_run_.Start(linear_model_, Eigen::Vector4d::Zero(), motor_torque[0],
                       with_sensitivities_ ? static_cast<int>(parameters_.size()) : 0,
                       kSwitchBudgetConstant + kSwitchesPerSample * static_cast<long>(samples_));
      return;
    }
    run_ = std::make_unique<HeldInputRun>(*integrator_, time, motor_torque, *this, "model");
  }

  void set_integration(DriveTrainIntegration integration) { integration_ = integration; }

  void Advance(std::size_t last, DriveTrainResponse* out) {
    last = std::min(last, samples_ == 0 ? 0 : samples_ - 1);
    const std::size_t count = samples_ == 0 || last < next_ ? 0 : last - next_ + 1;
    const std::size_t p = with_sensitivities_ ? parameters_.size() : 0;
    const std::size_t angle_samples = record_angles_ ? count : 0;
    out->link_torque.assign(count, 0.0);
    out->friction_mode.assign(angle_samples, 0);
    out->link_torque_sensitivity.assign(count * p, 0.0);
    out->motor_angle.assign(angle_samples, 0.0);
    out->deflection.assign(angle_samples, 0.0);
    out->motor_angle_sensitivity.assign(angle_samples * p, 0.0);
    out->deflection_sensitivity.assign(angle_samples * p, 0.0);
    out->switch_count = Switches();
    if (count == 0) return;
    out_ = out;
    window_first_ = next_;
    if (next_ == 0) Record(0);
    if (exact_) {
      AdvanceExact(last);
    } else {
      run_->RunTo(last);
    }
    next_ = last + 1;
    out->switch_count = Switches();
  }

  std::size_t next_sample() const { return next_; }

  // HeldInputSystem (sim/held_input_driver.h).
  void SetInput(double input) override {
    motor_torque_ = input;
    if (x_[kOmega] == 0.0) DecideModeAtRest();
    RefreshJacobian();
  }
  // A stuck reduced drive has no dynamics: state, sensitivities and the net
  // torque stay constant until the command changes.
  bool Frozen() const override { return model_ == DriveTrainModel::kReduced && mode_ == 0; }
  void Restart(double t) override { RestartIntegrator(t, with_sensitivities_); }
  void HandleSwitch() override { HandleSwitch(with_sensitivities_); }
  void CopyFromIntegrator() override { CopyFromIntegrator(with_sensitivities_); }
  void Record(std::size_t k) override { Record(k - window_first_, with_sensitivities_, out_); }

  DriveTrainModel model() const { return model_; }
  const std::vector<DriveTrainParameter>& parameters() const { return parameters_; }

 private:
  int Switches() const {
    if (exact_) return static_cast<int>(exact_run_.switches());
    return run_ ? run_->switches() : 0;
  }
  void AdvanceExact(std::size_t last) {
    const std::vector<double>& time = *time_;
    const std::vector<double>& torque = *torque_;
    for (std::size_t m = std::max<std::size_t>(next_, 1); m <= last; ++m) {
      exact_run_.Advance(time[m] - time[m - 1], torque[m - 1], time[m - 1]);
      const Eigen::Vector4d& x = exact_run_.state();
      for (int i = 0; i < n_; ++i) x_[static_cast<std::size_t>(i)] = x(i);
      const auto& s = exact_run_.sensitivities();
      for (std::size_t j = 0; j < s.size(); ++j) {
        for (int i = 0; i < n_; ++i) s_[j * static_cast<std::size_t>(n_) + static_cast<std::size_t>(i)] = s[j](i);
      }
      mode_ = exact_run_.mode();
      Record(m);
    }
  }

  double jacobian_cache(int col, int row) const { return jacobian_[static_cast<std::size_t>(col * n_ + row)]; }

  void RefreshJacobian() { CalcDriveTrainStateJacobian(params_, model_, mode_, jacobian_.data()); }

  // omega == 0: stuck if the friction can hold the net torque, else slide towards it.
  void DecideModeAtRest() {
    const double net = CalcNetTorque(params_, model_, motor_torque_, x_.data());
    mode_ = std::abs(net) <= params_.coulomb_friction ? 0 : Sign(net);
  }

  void RestartIntegrator(double t, bool with_sensitivities) {
    pointers_.clear();
    for (std::size_t j = 0; j < parameters_.size(); ++j) pointers_.push_back(&s_[j * static_cast<std::size_t>(n_)]);
    integrator_->Restart(t, x_.data(), pointers_, with_sensitivities);
  }

  void CopyFromIntegrator(bool with_sensitivities) {
    std::copy(integrator_->state(), integrator_->state() + n_, x_.begin());
    if (!with_sensitivities) return;
    for (std::size_t j = 0; j < parameters_.size(); ++j) {
      const double* s = integrator_->sensitivity(static_cast<int>(j));
      std::copy(s, s + n_, s_.begin() + static_cast<std::ptrdiff_t>(j * static_cast<std::size_t>(n_)));
    }
  }

  // A root stopped the integrator: switch the friction mode and apply the
  // sensitivity jump conditions (see the header).
  void HandleSwitch(bool with_sensitivities) {
    CopyFromIntegrator(with_sensitivities);
    const int old_mode = mode_;
    if (old_mode != 0) {
      double before[4];
      CalcDriveTrainDerivatives(params_, model_, motor_torque_, old_mode, x_.data(), before);
      const double omega_rate_before = before[kOmega];
      x_[kOmega] = 0.0;
      DecideModeAtRest();
      if (with_sensitivities && std::abs(omega_rate_before) > 0.0) {
        double after[4];
        CalcDriveTrainDerivatives(params_, model_, motor_torque_, mode_, x_.data(), after);
        for (std::size_t j = 0; j < parameters_.size(); ++j) {
          double* s = &s_[j * static_cast<std::size_t>(n_)];
          const double time_derivative = -s[kOmega] / omega_rate_before;  // dt*/dp_j
          for (int i = 0; i < n_; ++i) s[i] += (before[i] - after[i]) * time_derivative;
          s[kOmega] = mode_ == 0 ? 0.0 : s[kOmega];
        }
      }
    } else {
      const auto& fired = integrator_->root_directions();
      const double net = CalcNetTorque(params_, model_, motor_torque_, x_.data());
      mode_ = fired[0] != 0 ? 1 : (fired[1] != 0 ? -1 : Sign(net));
    }
    RefreshJacobian();
  }

  void Record(std::size_t k, bool with_sensitivities, DriveTrainResponse* out) const {
    out->link_torque[k] = CalcLinkTorque(params_, model_, x_.data());
    if (record_angles_) {
      out->friction_mode[k] = mode_;
      out->motor_angle[k] = x_[DriveTrainState::kMotorAngle];
      out->deflection[k] = CalcDeflection(params_, model_, x_.data());
    }
    if (!with_sensitivities) return;
    double gradient[4], deflection_gradient[4];
    CalcLinkTorqueStateGradient(params_, model_, gradient);
    if (record_angles_) CalcDeflectionStateGradient(params_, model_, deflection_gradient);
    const std::size_t p = parameters_.size();
    for (std::size_t j = 0; j < p; ++j) {
      const double* s = &s_[j * static_cast<std::size_t>(n_)];
      double value = CalcLinkTorqueParameterDerivative(params_, model_, x_.data(), parameters_[j]);
      for (int i = 0; i < n_; ++i) value += gradient[i] * s[i];
      out->link_torque_sensitivity[k * p + j] = value;
      if (!record_angles_) continue;  // (the deflection's derivative was 2 % of a reduced fit's time)
      double deflection = CalcDeflectionParameterDerivative(params_, model_, x_.data(), parameters_[j]);
      for (int i = 0; i < n_; ++i) deflection += deflection_gradient[i] * s[i];
      out->motor_angle_sensitivity[k * p + j] = s[DriveTrainState::kMotorAngle];
      out->deflection_sensitivity[k * p + j] = deflection;
    }
  }

  bool record_angles_ = true;
  DriveTrainModel model_;
  DriveTrainParameters params_;
  std::vector<DriveTrainParameter> parameters_;
  int n_;
  std::unique_ptr<CvodesIntegrator> integrator_;
  std::vector<double> jacobian_;
  std::vector<double> x_;
  std::vector<double> s_;  // sensitivities, parameter-major
  std::vector<const double*> pointers_;
  double motor_torque_ = 0.0;
  int mode_ = 0;
  bool with_sensitivities_ = false;
  DriveTrainResponse* out_ = nullptr;
  std::unique_ptr<HeldInputRun> run_;  // the simulation under way (Start, Advance)
  std::size_t samples_ = 0, next_ = 0;  // the log's samples; the next one to record
  std::size_t window_first_ = 0;        // the sample at index 0 of out_
  DriveTrainIntegration integration_ = DriveTrainIntegration::kExact;
  bool exact_ = false;                  // this run takes the exact path
  DriveTrainLinearModel linear_model_{model_, params_, parameters_};
  SwitchedLinearExact exact_run_;
  const std::vector<double>* time_ = nullptr;
  const std::vector<double>* torque_ = nullptr;
};

DriveTrainSimulator::DriveTrainSimulator(DriveTrainModel model, const DriveTrainParameters& nominal,
                                         std::vector<DriveTrainParameter> sensitivity_parameters,
                                         const SimulationTolerances& tolerances)
    : system_(std::make_unique<System>(model, nominal, std::move(sensitivity_parameters), tolerances)) {}

DriveTrainSimulator::~DriveTrainSimulator() = default;

void DriveTrainSimulator::Simulate(const DriveTrainParameters& params, const std::vector<double>& time,
                                   const std::vector<double>& motor_torque, bool with_sensitivities,
                                   DriveTrainResponse* response) {
  system_->Start(params, time, motor_torque, with_sensitivities);
  system_->Advance(time.empty() ? 0 : time.size() - 1, response);
}

void DriveTrainSimulator::Start(const DriveTrainParameters& params, const std::vector<double>& time,
                                const std::vector<double>& motor_torque, bool with_sensitivities) {
  system_->Start(params, time, motor_torque, with_sensitivities);
}

void DriveTrainSimulator::Advance(std::size_t last, DriveTrainResponse* response) { system_->Advance(last, response); }

std::size_t DriveTrainSimulator::next_sample() const { return system_->next_sample(); }

void DriveTrainSimulator::set_record_angles(bool record) { system_->set_record_angles(record); }

void DriveTrainSimulator::set_integration(DriveTrainIntegration integration) { system_->set_integration(integration); }

DriveTrainModel DriveTrainSimulator::model() const { return system_->model(); }

const std::vector<DriveTrainParameter>& DriveTrainSimulator::sensitivity_parameters() const {
  return system_->parameters();
}

}  // namespace driveid
