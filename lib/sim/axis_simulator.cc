#include "sim/axis_simulator.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/errors.h"
#include "models/axis_term.h"
#include "sim/cvodes_integrator.h"
#include "sim/held_input_driver.h"

namespace driveid {
namespace {
constexpr int kQ = 0, kV = 1;

int Sign(double value) { return (value > 0.0) - (value < 0.0); }

// The flow of v' = w - a v over a time t (a >= 0): with E = exp(-a t),
//   v(t) = v0 E + w phi1,  q(t) = q0 + v0 phi1 + w phi2,
//   phi1 = (1 - E) / a,  phi2 = (t - phi1) / a   (t and t^2 / 2 as a -> 0),
// and the derivatives dE/da = -t E, dphi1/da = (t E - phi1) / a,
// dphi2/da = -(dphi1/da + phi2) / a; series in x = a t below |x| 1e-3
// (truncation below 1e-15 relative, where the closed forms cancel).
struct Flow {
  double e, phi1, phi2, de, dphi1, dphi2;
};

Flow CalcFlow(double a, double t) {
  Flow f{};
  const double x = a * t;
  f.e = std::exp(-x);
  if (std::abs(x) < 1e-3) {
    f.phi1 = t * (1.0 - x / 2.0 + x * x / 6.0 - x * x * x / 24.0 + x * x * x * x / 120.0);
    f.phi2 = t * t * (0.5 - x / 6.0 + x * x / 24.0 - x * x * x / 120.0 + x * x * x * x / 720.0);
    f.dphi1 = t * t * (-0.5 + x / 3.0 - x * x / 8.0 + x * x * x / 30.0);
    f.dphi2 = t * t * t * (-1.0 / 6.0 + x / 12.0 - x * x / 40.0 + x * x * x / 180.0);
  } else {
    f.phi1 = -std::expm1(-x) / a;
    f.phi2 = (t - f.phi1) / a;
    f.dphi1 = (t * f.e - f.phi1) / a;
    f.dphi2 = -(f.dphi1 + f.phi2) / a;
  }
  f.de = -t * f.e;
  return f;
}
}  // namespace

class AxisSimulator::System final : public SensitivityOdeSystem, public HeldInputSystem {
 public:
  System(std::vector<int> terms, double position_tolerance, double rate_tolerance, bool allow_exact)
      : terms_(std::move(terms)), allow_exact_(allow_exact), inertia_(AxisIndex(&AxisParameters::inertia)),
        linear_(AxisLinearCount()) {
    for (int j : terms_) {
      if (j < 0 || j >= static_cast<int>(AxisParameterCount())) {
        throw std::logic_error("AxisSimulator: term index out of range");
      }
    }
    for (const AxisTerm* term : AxisTerms()) {
      if (!term->linear()) nonlinear_.push_back({term, AxisFirstIndex(*term)});
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
    jacobian[1] = -dq / theta_[inertia_];
    jacobian[2] = 1.0;
    jacobian[3] = -dv / theta_[inertia_];
  }
  void CalcSensitivityDerivative(double, const double* x, int j, const double* s, double* ds) const override {
    double dq = 0.0, dv = 0.0;
    ForceGradient(x, &dq, &dv);
    const auto term = static_cast<std::size_t>(terms_[static_cast<std::size_t>(j)]);
    double forcing = 0.0;
    if (term == inertia_) {
      forcing = -Acceleration(x) / theta_[inertia_];
    } else if (term < linear_) {
      forcing = -Regressors(x)[term] / theta_[inertia_];
    } else {
      const AxisTermParameter& owner = AxisParameterTerm(term);
      forcing = -owner.term->ForceParameterSlope(owner.row, &theta_[owner.first], x[kQ], x[kV], mode_) / theta_[inertia_];
    }
    ds[kQ] = s[kV];
    ds[kV] = (-dq * s[kQ] - dv * s[kV]) / theta_[inertia_] + forcing;
  }
  void CalcRoots(double, const double* x, double* g) const override { g[0] = x[kV]; }

  void Simulate(const AxisParameters& p, const std::vector<double>& time, const std::vector<double>& torque, double q0,
                double v0, bool with_sensitivities, AxisResponse* out) {
    theta_ = AxisValuesOf(p);
    if (!(theta_[inertia_] > 0.0)) throw IdentificationError("simulation: the axis needs inertia > 0");
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
    out->switch_count = ExactApplies() ? RunExact(time, torque) : RunHeldInput(*integrator_, time, torque, *this, "axis");
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
  AxisValues Regressors(const double* x) const { return CalcAxisRegressors(x[kQ], x[kV], 0.0, mode_); }
  // J v' = u - F, F the sum of all terms but the inertia.
  double Acceleration(const double* x) const {
    const AxisValues phi = Regressors(x);
    double force = 0.0;
    for (std::size_t j = 0; j < linear_; ++j) {
      if (j != inertia_) force += theta_[j] * phi[j];
    }
    for (const auto& [term, first] : nonlinear_) force += term->Force(&theta_[first], x[kQ], x[kV], mode_);
    return (u_ - force) / theta_[inertia_];
  }
  // dF/dq and dF/dv: the linear terms' regressor slopes, the others' own.
  void ForceGradient(const double* x, double* dq, double* dv) const {
    AxisValues d_dq{}, d_dv{};
    for (std::size_t j = 0; j < linear_;) {
      const AxisTermParameter& owner = AxisParameterTerm(j);
      owner.term->RegressorSlopes(x[kQ], x[kV], mode_, &d_dq[j], &d_dv[j]);
      while (j < linear_ && AxisParameterTerm(j).term == owner.term) ++j;
    }
    *dq = 0.0;
    *dv = 0.0;
    for (std::size_t j = 0; j < linear_; ++j) {
      if (j == inertia_) continue;
      *dq += theta_[j] * d_dq[j];
      *dv += theta_[j] * d_dv[j];
    }
    for (const auto& [term, first] : nonlinear_) *dv += term->ForceRateSlope(&theta_[first], x[kQ], x[kV], mode_);
  }
  // v = 0: stuck if friction holds the static torque, else slide towards it.
  // The static torque is u less every force at rest without a direction
  // (offset, gravity); the breakaway forward (backward) is what the forces
  // add moving forward (take moving backward) at v = 0: Coulomb, its
  // per-direction parts and any breakaway excess.
  void DecideModeAtRest() {
    const AxisValues still = CalcAxisRegressors(x_[kQ], 0.0, 0.0, 0), ahead = CalcAxisRegressors(x_[kQ], 0.0, 0.0, 1),
                     back = CalcAxisRegressors(x_[kQ], 0.0, 0.0, -1);
    double net = u_, forward = 0.0, backward = 0.0;
    for (std::size_t j = 0; j < linear_; ++j) {
      if (j == inertia_) continue;
      net -= theta_[j] * still[j];
      forward += theta_[j] * (ahead[j] - still[j]);
      backward += theta_[j] * (still[j] - back[j]);
    }
    for (const auto& [term, first] : nonlinear_) {
      const double* p = &theta_[first];
      const double at_rest = term->Force(p, x_[kQ], 0.0, 0);
      net -= at_rest;
      forward += term->Force(p, x_[kQ], 0.0, 1) - at_rest;
      backward += at_rest - term->Force(p, x_[kQ], 0.0, -1);
    }
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
    SwitchAtZeroRate(with_sensitivities);
  }
  void SwitchAtZeroRate(bool with_sensitivities) {
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

  // While the terms that are not mode-affine (gravity, a breakaway excess)
  // are 0 and not estimated, the axis is linear in v per friction mode: J v' = u - b_m v - c_m, with
  // b_m, c_m the rate and constant parts of the friction regressors. Each
  // held sample is then solved exactly (Flow), rate zero crossings in closed
  // form, so a torque that changes every sample costs no integrator restart.
  bool ExactApplies() const {
    if (!allow_exact_) return false;
    for (const AxisTerm* term : AxisTerms()) {
      if (term->mode_affine()) continue;
      const std::size_t first = AxisFirstIndex(*term);
      if (term->Present(&theta_[first])) return false;
      for (std::size_t i = 0; i < term->Rows().size(); ++i) {
        if (std::find(terms_.begin(), terms_.end(), static_cast<int>(first + i)) != terms_.end()) return false;
      }
    }
    return true;
  }

  // b_m / J = a, the acceleration at v = 0 (u - c_m) / J = w, and their
  // derivatives with respect to each estimated term, for the current mode:
  // each friction regressor is alpha_j + beta_j v in a mode.
  void ModeCoefficients(double* a, double* w, std::vector<double>* da, std::vector<double>* dw) const {
    const auto at_rest = CalcAxisRegressors(0.0, 0.0, 0.0, mode_), moving = CalcAxisRegressors(0.0, 1.0, 0.0, mode_);
    const double inertia = theta_[inertia_];
    double rate_part = 0.0, constant_part = 0.0;
    for (std::size_t j = 0; j < linear_; ++j) {
      if (j == inertia_ || !AxisParameterTerm(j).term->mode_affine()) continue;  // 0 on this path
      rate_part += theta_[j] * (moving[j] - at_rest[j]);
      constant_part += theta_[j] * at_rest[j];
    }
    *a = rate_part / inertia;
    *w = (u_ - constant_part) / inertia;
    if (da == nullptr) return;
    da->assign(terms_.size(), 0.0);
    dw->assign(terms_.size(), 0.0);
    for (std::size_t i = 0; i < terms_.size(); ++i) {
      const auto j = static_cast<std::size_t>(terms_[i]);
      if (j == inertia_) {
        (*da)[i] = -*a / inertia;
        (*dw)[i] = -*w / inertia;
      } else {
        (*da)[i] = (moving[j] - at_rest[j]) / inertia;
        (*dw)[i] = -at_rest[j] / inertia;
      }
    }
  }

  // Advances the sliding state (and its sensitivities) by t in the current
  // mode: the flow's derivatives by a and w times those of a and w.
  void Advance(double t, double a, double w, const std::vector<double>& da, const std::vector<double>& dw) {
    const Flow f = CalcFlow(a, t);
    const double v0 = x_[kV];
    if (with_sensitivities_) {
      for (std::size_t i = 0; i < terms_.size(); ++i) {
        const double sq = s_[2 * i], sv = s_[2 * i + 1];
        s_[2 * i] = sq + sv * f.phi1 + (v0 * f.dphi1 + w * f.dphi2) * da[i] + dw[i] * f.phi2;
        s_[2 * i + 1] = sv * f.e + (v0 * f.de + w * f.dphi1) * da[i] + dw[i] * f.phi1;
      }
    }
    x_[kQ] += v0 * f.phi1 + w * f.phi2;
    x_[kV] = v0 * f.e + w * f.phi1;
  }

  // The held-sample loop of sim/held_input_driver.h, solved exactly: per
  // sample the mode at rest is decided from the new torque, a sliding axis
  // flows to the sample or to its rate's zero crossing (closed form: for
  // v0 w < 0, E* = w / (w - a v0), t* = log1p(-a v0 / w) / a, -v0 / w as
  // a -> 0), where it sticks or reverses with the jump conditions of the
  // header; at most two pieces per sample (a reversal cannot cross again).
  int RunExact(const std::vector<double>& time, const std::vector<double>& torque) {
    int switches = 0;
    double a = 0.0, w = 0.0;
    std::vector<double> da, dw;
    for (std::size_t k = 1; k < time.size(); ++k) {
      SetInput(torque[k - 1]);
      double left = time[k] - time[k - 1];
      for (int piece = 0; piece < 3 && left > 0.0 && mode_ != 0; ++piece) {
        ModeCoefficients(&a, &w, with_sensitivities_ ? &da : nullptr, &dw);
        const double v0 = x_[kV];
        double crossing = HUGE_VAL;
        if (v0 * w < 0.0) crossing = a > 0.0 ? std::log1p(-a * v0 / w) / a : -v0 / w;
        if (!(crossing < left)) {
          Advance(left, a, w, da, dw);
          left = 0.0;
          break;
        }
        Advance(crossing, a, w, da, dw);
        left -= crossing;
        ++switches;
        SwitchAtZeroRate(with_sensitivities_);
      }
      if (mode_ != 0 && left > 0.0) {
        throw IdentificationError(fmt::format("simulation: the axis switches mode more than twice in the sample at "
                                              "t = {} s (chattering)", time[k - 1]));
      }
      Record(k, with_sensitivities_, out_);
    }
    return switches;
  }

  std::vector<int> terms_;
  bool allow_exact_ = true;
  std::unique_ptr<CvodesIntegrator> integrator_;
  std::size_t inertia_;  // J's index
  std::size_t linear_;   // the linear parameters' count
  std::vector<std::pair<const AxisTerm*, std::size_t>> nonlinear_;  // with their first index
  AxisValues theta_{};
  std::array<double, 2> x_{};
  std::vector<double> s_;
  std::vector<const double*> pointers_;
  double u_ = 0.0;
  int mode_ = 0;
  bool with_sensitivities_ = false;
  AxisResponse* out_ = nullptr;
};

AxisSimulator::AxisSimulator(std::vector<int> terms, double position_tolerance, double rate_tolerance,
                             bool allow_exact)
    : system_(std::make_unique<System>(std::move(terms), position_tolerance, rate_tolerance, allow_exact)) {}

AxisSimulator::~AxisSimulator() = default;

void AxisSimulator::Simulate(const AxisParameters& p, const std::vector<double>& time,
                             const std::vector<double>& torque, double q0, double v0, bool with_sensitivities,
                             AxisResponse* response) {
  system_->Simulate(p, time, torque, q0, v0, with_sensitivities, response);
}

}  // namespace driveid
