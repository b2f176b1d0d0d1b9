// The exact simulation of sim/switched_linear_exact.h.
#include "sim/switched_linear_exact.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <unsupported/Eigen/MatrixFunctions>
#include <fmt/format.h>

#include "core/errors.h"

namespace driveid {
namespace {
using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Matrix10 = Eigen::Matrix<double, 10, 10>;
using Vector4 = Eigen::Vector4d;
constexpr int kRate = SwitchedLinearExact::kRate;

int Sign(double value) { return (value > 0.0) - (value < 0.0); }

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

void SwitchedLinearExact::Start(const SwitchedLinearModel& model, const Vector4& x0, double u0, int sensitivities,
                                long switch_budget) {
  model_ = &model;
  coulomb_ = model.Coulomb();
  const auto np = static_cast<std::size_t>(std::max(sensitivities, 0));
  initial_index_.clear();
  for (std::size_t j = 0; j < np; ++j) initial_index_.push_back(model.InitialStateIndex(static_cast<int>(j)));
  for (int mode = -1; mode <= 1; ++mode) {
    fields_[mode + 1] = model.Field(mode);
    radius_[mode + 1] = Eigen::EigenSolver<Eigen::Matrix4d>(fields_[mode + 1].a, false).eigenvalues().cwiseAbs().maxCoeff();
    derivatives_[mode + 1].clear();
    for (std::size_t j = 0; j < np; ++j) derivatives_[mode + 1].push_back(model.FieldDerivative(mode, static_cast<int>(j)));
  }
  cache_.clear();
  x_ = x0;
  s_.assign(np, Vector4::Zero());
  u_ = u0;
  mode_ = Sign(x_(kRate));
  if (mode_ == 0) DecideModeAtRest();
  for (std::size_t j = 0; j < np; ++j) {
    const int i = initial_index_[j];
    // (a stuck body's rate is held at 0: no sensitivity to its start value)
    if (i >= 0 && !(mode_ == 0 && i == kRate)) s_[j](i) = 1.0;
  }
  switches_ = 0;
  budget_ = switch_budget;
}

// The transitions of the current mode over `length`, cached per mode and
// length (a log's intervals are equal to rounding).
const SwitchedLinearExact::Transitions& SwitchedLinearExact::Transition(double length) {
  for (const auto& t : cache_) {
    if (t.mode == mode_ && std::abs(t.length - length) <= 1e-12 * length) return t;
  }
  if (cache_.size() >= 32) cache_.clear();  // irregular stamps: no reuse to speak of
  cache_.push_back(Make(length));
  return cache_.back();
}

// Initial-state sensitivities need no block exponential: they move with the
// state's own transition.
SwitchedLinearExact::Transitions SwitchedLinearExact::Make(double length) const {
  Transitions t;
  t.length = length;
  t.mode = mode_;
  const ModeField& f = fields_[mode_ + 1];
  t.state = StateTransition(f, length);
  t.half = StateTransition(f, 0.5 * length);
  const double a_norm = f.a.cwiseAbs().colwise().sum().maxCoeff();
  for (std::size_t j = 0; j < s_.size(); ++j) {
    if (initial_index_[j] >= 0) {
      t.sensitivity.push_back(Eigen::Matrix<double, 8, 10>::Zero());
      continue;
    }
    // A derivative block much larger than A (the derivative by a small
    // inertia) would make the exponential's scaling and squaring lose the
    // state block: the sensitivity to sigma p_j is exponentiated instead,
    // sigma a power of 2 that brings dA_j to A's size, and scaled back.
    ModeField g = derivatives_[mode_ + 1][j];
    const double g_norm = g.a.cwiseAbs().colwise().sum().maxCoeff();
    int exponent = 0;
    if (a_norm > 0.0 && g_norm > a_norm) std::frexp(g_norm / a_norm, &exponent);
    const double sigma = std::ldexp(1.0, -exponent);
    g.a *= sigma;
    g.c *= sigma;
    g.b *= sigma;
    Eigen::Matrix<double, 8, 10> e = SensitivityTransition(f, g, length);
    e.block<4, 4>(4, 0) /= sigma;
    e.block<4, 2>(4, 8) /= sigma;
    t.sensitivity.push_back(e);
  }
  return t;
}

Vector4 SwitchedLinearExact::Propagate(const Eigen::Matrix<double, 4, 6>& e, const Vector4& x) const {
  return e.leftCols<4>() * x + e.col(4) + e.col(5) * u_;
}

void SwitchedLinearExact::Apply(const Transitions& t) {
  for (std::size_t j = 0; j < s_.size(); ++j) {
    if (initial_index_[j] >= 0) {
      s_[j] = t.state.leftCols<4>() * s_[j];
      continue;
    }
    const auto& e = t.sensitivity[j];
    s_[j] = e.block<4, 4>(4, 0) * x_ + e.block<4, 4>(4, 4) * s_[j] + e.block<4, 1>(4, 8) + e.block<4, 1>(4, 9) * u_;
  }
  x_ = Propagate(t.state, x_);
}

// The event function of the mode: the sliding body's rate (times the mode),
// or the margin of the stuck body's static torque to its friction.
double SwitchedLinearExact::Margin(const Vector4& x) const {
  if (mode_ != 0) return mode_ * x(kRate);
  return coulomb_ - std::abs(model_->StaticTorque(x, u_));
}

// Whether a margin lets the mode go on: a sliding body stops where its rate
// reaches 0; a stuck body holds while |N| <= c (as DecideModeAtRest), so a
// margin of exactly 0 (N = c, or c = 0 with N = 0) is no event.
bool SwitchedLinearExact::Clear(double margin) const { return mode_ == 0 ? margin >= 0.0 : margin > 0.0; }

// At rest: stuck if the friction holds the static torque, else slide towards it.
void SwitchedLinearExact::DecideModeAtRest() {
  const double net = model_->StaticTorque(x_, u_);
  mode_ = std::abs(net) <= coulomb_ ? 0 : Sign(net);
}

// One held interval, with the events inside it. Whole intervals use the
// cached exponentials; pieces between events the Taylor series.
void SwitchedLinearExact::Advance(double length, double u, double start) {
  u_ = u;
  if (x_(kRate) == 0.0) DecideModeAtRest();
  double left = length;
  while (left > 0.0) {
    const bool whole = left == length;
    const ModeField& f = fields_[mode_ + 1];
    const Transitions* full = whole ? &Transition(length) : nullptr;
    const Vector4 end = whole ? Propagate(full->state, x_) : PropagateBySeries(f, x_, left);
    const double mid_margin = Margin(whole ? Propagate(full->half, x_) : PropagateBySeries(f, x_, 0.5 * left));
    if (Clear(Margin(end)) && Clear(mid_margin)) {
      if (whole) {
        Apply(*full);
      } else {
        AdvanceBySeries(left);
      }
      return;
    }
    const double hit = LocateEvent(Clear(Margin(end)) ? 0.5 * left : left);
    AdvanceBySeries(hit);
    HandleSwitch();
    if (++switches_ > budget_) {
      throw IdentificationError(
          fmt::format("simulation: more than {} stick/slip switches before t = {} s (chattering)", budget_, start));
    }
    left -= hit;
    if (hit <= 0.0) left = std::nextafter(left, 0.0);  // (never loops on one point)
  }
}

// Advances x and the sensitivities over `length` (a piece between events,
// of arbitrary length: no reuse of exponentials) by the Taylor series of
// exp(M length) applied to z = (x, s_1 .. s_P): z' = M z with
// x' = A x + c + b u and s_j' = A s_j + dA_j x + dc_j + db_j u, in pieces
// short enough (spectral radius of A times h <= 1/2; the sensitivity blocks
// share A's spectrum) that 40 terms reach rounding.
void SwitchedLinearExact::AdvanceBySeries(double length) {
  if (!(length > 0.0)) return;
  const ModeField& f = fields_[mode_ + 1];
  const auto& g = derivatives_[mode_ + 1];
  const std::size_t np = s_.size();
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

// The state after `tau` in the current mode from x (no sensitivities): the
// Taylor series of the exact solution in pieces as AdvanceBySeries, far
// cheaper than an exponential of the augmented matrix for the many short
// spans an event search and the pieces after an event need.
Vector4 SwitchedLinearExact::PropagateBySeries(const ModeField& f, const Vector4& x0, double tau) const {
  Vector4 x = x0;
  if (!(tau > 0.0)) return x;
  const int pieces = std::max(1, static_cast<int>(std::ceil(2.0 * radius_[mode_ + 1] * tau)));
  const double h = tau / pieces;
  for (int piece = 0; piece < pieces; ++piece) {
    Vector4 term = f.a * x + f.c + f.b * u_;
    for (int k = 1; k <= 40; ++k) {
      term *= h / k;
      x += term;
      if (term.cwiseAbs().maxCoeff() <= 1e-17 * x.cwiseAbs().maxCoeff()) break;
      term = f.a * term;
    }
  }
  return x;
}

// The first time in (0, upper] where the margin reaches 0 (it is > 0 at 0
// and <= 0 at upper): Newton steps on the exact solution (the margin's rate
// from the field), kept inside the bracket, else bisection; each step aims
// just past its root so that the bracket closes from both sides.
double SwitchedLinearExact::LocateEvent(double upper) const {
  const ModeField& f = fields_[mode_ + 1];
  const double tolerance = 1e-13 * upper;
  double lo = 0.0, hi = upper, tau = 0.0;
  Vector4 x = x_;
  for (int iteration = 0; iteration < 100 && hi - lo > tolerance; ++iteration) {
    if (iteration > 0) x = PropagateBySeries(f, x_, tau);
    const double margin = Margin(x);
    if (iteration > 0) (Clear(margin) ? lo : hi) = tau;  // (at 0 it may start at 0, as a body that breaks away)
    const double rate = MarginRate(x, f);
    double next = rate != 0.0 ? tau - margin / rate + (Clear(margin) ? 0.25 : -0.25) * tolerance : lo - 1.0;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    tau = next;
  }
  return hi;
}

// d Margin / dt along the mode's field at x.
double SwitchedLinearExact::MarginRate(const Vector4& x, const ModeField& f) const {
  const Vector4 dx = f.a * x + f.c + f.b * u_;
  if (mode_ != 0) return mode_ * dx(kRate);
  return -Sign(model_->StaticTorque(x, u_)) * model_->StaticTorqueRate(dx);
}

void SwitchedLinearExact::HandleSwitch() {
  const ModeField before_field = fields_[mode_ + 1];
  if (mode_ != 0) {
    const Vector4 before = before_field.a * x_ + before_field.c + before_field.b * u_;
    x_(kRate) = 0.0;
    DecideModeAtRest();
    const ModeField& after_field = fields_[mode_ + 1];
    const Vector4 after = after_field.a * x_ + after_field.c + after_field.b * u_;
    if (s_.empty() || before(kRate) == 0.0) return;
    for (auto& s : s_) {
      const double time_derivative = -s(kRate) / before(kRate);  // dt*/dp_j
      s += (before - after) * time_derivative;
      if (mode_ == 0) s(kRate) = 0.0;
    }
  } else {
    // Break-away: the field is continuous there, nothing jumps.
    mode_ = Sign(model_->StaticTorque(x_, u_));
  }
}

}  // namespace driveid
