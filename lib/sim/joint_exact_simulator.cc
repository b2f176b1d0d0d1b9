// The joint simulator's exact path (sim/joint_simulator.h): without gravity
// the joint is linear within a friction mode, x' = A x + c + b u with u held
// over a sample, so each interval is one matrix exponential
//   [x; 1; u](t + T) = exp([A c b; 0 0 0] T) [x; 1; u](t)
// and a sensitivity s_j = dx/dp_j follows s_j' = A s_j + dA_j x + dc_j + db_j u,
// the same with the 10 x 10 block matrix [[A 0 c b]; [dA_j A dc_j db_j]; 0].
// The exponentials are computed once per mode and interval length. A mode
// event inside an interval (the sliding motor's rate reaching 0, the stuck
// motor's static torque leaving [-c_m, c_m]), seen at the interval's end or
// its midpoint, is located by bisection on the exact solution and handled as the integrator's root (the same jump conditions).
#include <cmath>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <unsupported/Eigen/MatrixFunctions>
#include <fmt/format.h>

#include "core/errors.h"
#include "sim/joint_exact_simulator.h"
#include "sim/joint_simulator.h"

namespace driveid {
namespace {
constexpr int kOmegaM = 1, kThetaL = 2, kOmegaL = 3;
constexpr long kSwitchesPerSample = 4, kSwitchBudgetConstant = 2000;

using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Matrix10 = Eigen::Matrix<double, 10, 10>;
using Vector4 = Eigen::Vector4d;

int Sign(double value) { return (value > 0.0) - (value < 0.0); }

// The linear field of one mode and its parameter derivatives.
struct ModeField {
  Eigen::Matrix4d a = Eigen::Matrix4d::Zero();
  Vector4 c = Vector4::Zero(), b = Vector4::Zero();
};

ModeField Field(const JointParameters& p, int mode) {
  ModeField f;
  const double jm = p.motor_inertia, jl = p.link_inertia, k = p.stiffness, d = p.damping;
  if (mode != 0) {
    f.a.row(0) << 0.0, 1.0, 0.0, 0.0;
    f.a.row(1) << -k / jm, -(d + p.motor_viscous) / jm, k / jm, d / jm;
    f.c(1) = (-p.motor_coulomb * mode - p.offset) / jm;
    f.b(1) = 1.0 / jm;
  }
  f.a.row(2) << 0.0, 0.0, 0.0, 1.0;
  f.a.row(3) << k / jl, d / jl, -k / jl, -(d + p.link_viscous) / jl;
  return f;
}

ModeField FieldDerivative(const JointParameters& p, int mode, int term) {
  const ModeField f = Field(p, mode);
  ModeField g;
  const double jm = p.motor_inertia, jl = p.link_inertia;
  const double motor = mode != 0 ? 1.0 / jm : 0.0;  // the motor rows vanish while stuck
  switch (term) {
    case kJointMotorInertia:
      g.a.row(1) = -f.a.row(1) / jm;
      g.c(1) = -f.c(1) / jm;
      g.b(1) = -f.b(1) / jm;
      break;
    case kJointLinkInertia: g.a.row(3) = -f.a.row(3) / jl; break;
    case kJointStiffness:
      g.a.row(1) << -motor, 0.0, motor, 0.0;
      g.a.row(3) << 1.0 / jl, 0.0, -1.0 / jl, 0.0;
      break;
    case kJointDamping:
      g.a.row(1) << 0.0, -motor, 0.0, motor;
      g.a.row(3) << 0.0, 1.0 / jl, 0.0, -1.0 / jl;
      break;
    case kJointMotorViscous: g.a(1, 1) = -motor; break;
    case kJointMotorCoulomb: g.c(1) = -mode * motor; break;
    case kJointLinkViscous: g.a(3, 3) = -1.0 / jl; break;
    case kJointOffset: g.c(1) = -motor; break;
    default: break;
  }
  return g;
}

// exp of the state's augmented matrix over tau: rows of x, columns (x, 1, u).
Eigen::Matrix<double, 4, 6> StateTransition(const ModeField& f, double tau) {
  Matrix6 m = Matrix6::Zero();
  m.block<4, 4>(0, 0) = f.a * tau;
  m.block<4, 1>(0, 4) = f.c * tau;
  m.block<4, 1>(0, 5) = f.b * tau;
  return m.exp().topRows<4>();
}

// exp of the sensitivity's block matrix: rows of (x, s_j), columns (x, s_j, 1, u).
Eigen::Matrix<double, 8, 10> SensitivityTransition(const ModeField& f, const ModeField& g, double tau) {
  Matrix10 m = Matrix10::Zero();
  m.block<4, 4>(0, 0) = f.a * tau;
  m.block<4, 1>(0, 8) = f.c * tau;
  m.block<4, 1>(0, 9) = f.b * tau;
  m.block<4, 4>(4, 0) = g.a * tau;
  m.block<4, 4>(4, 4) = f.a * tau;
  m.block<4, 1>(4, 8) = g.c * tau;
  m.block<4, 1>(4, 9) = g.b * tau;
  return m.exp().topRows<8>();
}

}  // namespace

class JointExactSimulator::Impl {
 public:
  explicit Impl(std::vector<int> terms) : terms_(std::move(terms)) {}

  void Simulate(const JointParameters& p, const std::vector<double>& time, const std::vector<double>& torque,
                const std::array<double, 4>& x0, bool with_sensitivities, JointStateResponse* out) {
    p_ = p;
    const std::size_t samples = time.size(), np = terms_.size();
    sensitivities_ = with_sensitivities && np > 0;
    out->state.assign(samples * 4, 0.0);
    out->sensitivity.assign(sensitivities_ ? samples * np * 4 : 0, 0.0);
    out->mode.assign(samples, 0);
    out->switch_count = 0;
    if (samples == 0) return;
    for (int mode = -1; mode <= 1; ++mode) {
      fields_[mode + 1] = Field(p, mode);
      radius_[mode + 1] = Eigen::EigenSolver<Eigen::Matrix4d>(fields_[mode + 1].a, false).eigenvalues().cwiseAbs().maxCoeff();
      derivatives_[mode + 1].clear();
      for (int term : terms_) derivatives_[mode + 1].push_back(FieldDerivative(p, mode, term));
    }
    cache_.clear();
    x_ = Vector4(x0[0], x0[1], x0[2], x0[3]);
    s_.assign(np, Vector4::Zero());
    u_ = torque[0];
    mode_ = Sign(x_(kOmegaM));
    if (mode_ == 0) DecideModeAtRest();
    for (std::size_t j = 0; j < np; ++j) {
      const int i = InitialStateIndex(terms_[j]);
      // (a stuck motor's rate is held at 0: no sensitivity to its start value)
      if (i >= 0 && !(mode_ == 0 && i == kOmegaM)) s_[j](i) = 1.0;
    }
    switches_ = 0;
    const long budget = kSwitchBudgetConstant + kSwitchesPerSample * static_cast<long>(samples);
    Record(0, out);
    for (std::size_t k = 0; k + 1 < samples; ++k) {
      u_ = torque[k];
      if (x_(kOmegaM) == 0.0) DecideModeAtRest();
      Interval(time[k + 1] - time[k], budget, time[k]);
      Record(k + 1, out);
    }
    out->switch_count = static_cast<int>(switches_);  // at most the budget
  }

 private:
  struct Transitions {
    double length = 0.0;
    int mode = 0;
    Eigen::Matrix<double, 4, 6> state, half;  // over length and length / 2
    std::vector<Eigen::Matrix<double, 8, 10>> sensitivity;
  };

  // The transitions of the current mode over `length`, cached per mode and
  // length (a log's intervals are equal to rounding).
  const Transitions& Transition(double length) {
    for (const auto& t : cache_) {
      if (t.mode == mode_ && std::abs(t.length - length) <= 1e-12 * length) return t;
    }
    if (cache_.size() >= 32) cache_.clear();  // irregular stamps: no reuse to speak of
    cache_.push_back(Make(length));
    return cache_.back();
  }
  // Initial-state terms need no block exponential: their sensitivity moves
  // with the state's own transition.
  Transitions Make(double length) const {
    Transitions t;
    t.length = length;
    t.mode = mode_;
    const ModeField& f = fields_[mode_ + 1];
    t.state = StateTransition(f, length);
    t.half = StateTransition(f, 0.5 * length);
    if (sensitivities_) {
      for (std::size_t j = 0; j < terms_.size(); ++j) {
        t.sensitivity.push_back(InitialStateIndex(terms_[j]) >= 0
                                    ? Eigen::Matrix<double, 8, 10>::Zero()
                                    : SensitivityTransition(f, derivatives_[mode_ + 1][j], length));
      }
    }
    return t;
  }
  Vector4 Propagate(const Eigen::Matrix<double, 4, 6>& e, const Vector4& x) const {
    return e.leftCols<4>() * x + e.col(4) + e.col(5) * u_;
  }
  void Apply(const Transitions& t) {
    if (sensitivities_) {
      for (std::size_t j = 0; j < s_.size(); ++j) {
        if (InitialStateIndex(terms_[j]) >= 0) {
          s_[j] = t.state.leftCols<4>() * s_[j];
          continue;
        }
        const auto& e = t.sensitivity[j];
        s_[j] = e.block<4, 4>(4, 0) * x_ + e.block<4, 4>(4, 4) * s_[j] + e.block<4, 1>(4, 8) + e.block<4, 1>(4, 9) * u_;
      }
    }
    x_ = Propagate(t.state, x_);
  }
  // The event function of the mode: the sliding motor's rate (times the
  // mode), or the margin of the stuck motor's static torque to its friction.
  double Margin(const Vector4& x) const {
    if (mode_ != 0) return mode_ * x(kOmegaM);
    return p_.motor_coulomb - std::abs(StaticTorque(x));
  }
  double StaticTorque(const Vector4& x) const {
    return u_ - p_.stiffness * (x(0) - x(kThetaL)) + p_.damping * x(kOmegaL) - p_.offset;
  }
  void DecideModeAtRest() {
    const double net = StaticTorque(x_);
    mode_ = std::abs(net) <= p_.motor_coulomb ? 0 : Sign(net);
  }

  // One held interval, with the events inside it. Whole intervals use the
  // cached exponentials; pieces between events the Taylor series.
  void Interval(double length, long budget, double start) {
    double left = length;
    while (left > 0.0) {
      const bool whole = left == length;
      const ModeField& f = fields_[mode_ + 1];
      const Transitions* full = whole ? &Transition(length) : nullptr;
      const Vector4 end = Propagate(whole ? full->state : StateTransition(f, left), x_);
      const double mid_margin = Margin(Propagate(whole ? full->half : StateTransition(f, 0.5 * left), x_));
      if (Margin(end) > 0.0 && mid_margin > 0.0) {
        if (whole) {
          Apply(*full);
        } else {
          AdvanceBySeries(left);
        }
        return;
      }
      const double hit = LocateEvent(Margin(end) > 0.0 ? 0.5 * left : left);
      AdvanceBySeries(hit);
      HandleSwitch();
      if (++switches_ > budget) {
        throw IdentificationError(fmt::format(
            "simulation: more than {} stick/slip switches before t = {} s (chattering)", budget, start));
      }
      left -= hit;
      if (hit <= 0.0) left = std::nextafter(left, 0.0);  // (never loops on one point)
    }
  }

  // Advances x and the sensitivities over `length` (a piece between events,
  // of arbitrary length: no reuse of exponentials) by the Taylor series of
  // exp(M length) applied to z = (x, s_1 .. s_P): z' = M z with
  // x' = A x + c + b u and s_j' = A s_j + dA_j x + dc_j + db_j u, in pieces
  // short enough (spectral radius of A times h <= 1/2; the sensitivity
  // blocks share A's spectrum) that 40 terms reach rounding.
  void AdvanceBySeries(double length) {
    if (!(length > 0.0)) return;
    const ModeField& f = fields_[mode_ + 1];
    const auto& g = derivatives_[mode_ + 1];
    const std::size_t np = sensitivities_ ? s_.size() : 0;
    const int pieces = std::max(1, static_cast<int>(std::ceil(2.0 * radius_[mode_ + 1] * length)));
    const double h = length / pieces;
    std::vector<Vector4> term_s(np), next_s(np);
    for (int piece = 0; piece < pieces; ++piece) {
      Vector4 term_x = x_;
      for (std::size_t j = 0; j < np; ++j) term_s[j] = s_[j];
      for (int k = 1; k <= 40; ++k) {
        const double scale = h / k;
        // The constant columns (c, b u) enter the first term only.
        Vector4 next_x = f.a * term_x;
        if (k == 1) next_x += f.c + f.b * u_;
        for (std::size_t j = 0; j < np; ++j) {
          next_s[j] = f.a * term_s[j] + g[j].a * term_x;
          if (k == 1) next_s[j] += g[j].c + g[j].b * u_;
          next_s[j] *= scale;
          s_[j] += next_s[j];
          term_s[j] = next_s[j];
        }
        next_x *= scale;
        x_ += next_x;
        term_x = next_x;
        bool converged = next_x.cwiseAbs().maxCoeff() <= 1e-17 * x_.cwiseAbs().maxCoeff();
        for (std::size_t j = 0; j < np && converged; ++j) {
          converged = next_s[j].cwiseAbs().maxCoeff() <= 1e-17 * s_[j].cwiseAbs().maxCoeff();
        }
        if (converged) break;
      }
    }
  }

  // The first time in (0, upper] where the margin reaches 0 (it is > 0 at 0
  // and <= 0 at upper): Newton steps on the exact solution (the margin's
  // rate from the field), kept inside the bracket, else bisection; each
  // step aims just past its root so that the bracket closes from both sides.
  double LocateEvent(double upper) const {
    const ModeField& f = fields_[mode_ + 1];
    const double tolerance = 1e-13 * upper;
    double lo = 0.0, hi = upper, tau = 0.0;
    Vector4 x = x_;
    for (int iteration = 0; iteration < 100 && hi - lo > tolerance; ++iteration) {
      if (iteration > 0) x = Propagate(StateTransition(f, tau), x_);
      const double margin = Margin(x);
      if (iteration > 0) (margin > 0.0 ? lo : hi) = tau;  // (at 0 it may start at 0, as a motor that breaks away)
      const double rate = MarginRate(x, f);
      double next = rate != 0.0 ? tau - margin / rate + (margin > 0.0 ? 0.25 : -0.25) * tolerance : lo - 1.0;
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      tau = next;
    }
    return hi;
  }
  // d Margin / dt along the mode's field at x.
  double MarginRate(const Vector4& x, const ModeField& f) const {
    const Vector4 dx = f.a * x + f.c + f.b * u_;
    if (mode_ != 0) return mode_ * dx(kOmegaM);
    const double static_rate = -p_.stiffness * (dx(0) - dx(kThetaL)) + p_.damping * dx(kOmegaL);
    return -Sign(StaticTorque(x)) * static_rate;
  }

  void HandleSwitch() {
    const ModeField before_field = fields_[mode_ + 1];
    if (mode_ != 0) {
      const Vector4 before = before_field.a * x_ + before_field.c + before_field.b * u_;
      x_(kOmegaM) = 0.0;
      DecideModeAtRest();
      const ModeField& after_field = fields_[mode_ + 1];
      const Vector4 after = after_field.a * x_ + after_field.c + after_field.b * u_;
      if (!sensitivities_ || before(kOmegaM) == 0.0) return;
      for (auto& s : s_) {
        const double time_derivative = -s(kOmegaM) / before(kOmegaM);  // dt*/dp_j
        s += (before - after) * time_derivative;
        if (mode_ == 0) s(kOmegaM) = 0.0;
      }
    } else {
      // Break-away: the field is continuous there, nothing jumps.
      mode_ = Sign(StaticTorque(x_));
    }
  }

  void Record(std::size_t k, JointStateResponse* out) const {
    for (int i = 0; i < 4; ++i) out->state[4 * k + static_cast<std::size_t>(i)] = x_(i);
    out->mode[k] = mode_;
    if (!sensitivities_) return;
    const std::size_t np = s_.size();
    for (std::size_t j = 0; j < np; ++j) {
      for (int i = 0; i < 4; ++i) out->sensitivity[(k * np + j) * 4 + static_cast<std::size_t>(i)] = s_[j](i);
    }
  }

  std::vector<int> terms_;
  JointParameters p_;
  bool sensitivities_ = false;
  std::array<ModeField, 3> fields_;
  std::array<double, 3> radius_{};  // spectral radius of each mode's A [1/s]
  std::array<std::vector<ModeField>, 3> derivatives_;
  std::vector<Transitions> cache_;
  Vector4 x_;
  std::vector<Vector4> s_;
  double u_ = 0.0;
  int mode_ = 0;
  long switches_ = 0;
};

JointExactSimulator::JointExactSimulator(std::vector<int> terms) : impl_(std::make_unique<Impl>(std::move(terms))) {}

JointExactSimulator::~JointExactSimulator() = default;

void JointExactSimulator::Simulate(const JointParameters& p, const std::vector<double>& time,
                                   const std::vector<double>& motor_torque, const std::array<double, 4>& x0,
                                   bool with_sensitivities, JointStateResponse* response) {
  impl_->Simulate(p, time, motor_torque, x0, with_sensitivities, response);
}

}  // namespace driveid
