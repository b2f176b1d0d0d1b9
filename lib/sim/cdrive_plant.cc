#include "sim/cdrive_plant.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/errors.h"
#include "sim/cvodes_integrator.h"

namespace driveid {
namespace {

constexpr int kContacts = 3;
constexpr double kDirection[kContacts][2] = {{1.0, 0.0}, {0.0, 1.0}, {1.0, -1.0}};
constexpr double kZeroRate = 1e-9;  // rad/s: below this a contact velocity counts as zero
constexpr int kStateSize = 4;       // psi_L, psi_R, psi_L', psi_R'

double Dot(const double* g, const Vector2& v) { return g[0] * v[0] + g[1] * v[1]; }

// Friction mode: per contact -1/+1 sliding or 0 stuck.
using Mode = std::array<int, kContacts>;

bool AllowedStuckSet(const Mode& mode) {
  const int stuck = (mode[0] == 0) + (mode[1] == 0) + (mode[2] == 0);
  return stuck <= 1 || stuck == 3;
}

}  // namespace

class CDrivePlant::System final : public SensitivityOdeSystem {
 public:
  explicit System(const CDriveParameters& params) : params_(params) {
    const Matrix2 m = CalcCDriveInertiaMatrix(params);
    const double determinant = m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0);
    if (!(determinant > 0.0) || !(m(0, 0) > 0.0)) {
      throw InputError("cdrive: the inertia matrix M is not positive definite (check I_h, I_c, m)");
    }
    inverse_ << m(1, 1) / determinant, -m(0, 1) / determinant, -m(1, 0) / determinant, m(0, 0) / determinant;
    damping_ = CalcCDriveDampingMatrix(params);
    limit_ = {params.coulomb_motor, params.coulomb_motor, params.coulomb_collar};
    IntegratorOptions options;
    options.relative_tolerance = 1e-8;
    options.absolute_tolerance = {1e-9, 1e-9, 1e-7, 1e-7};
    integrator_ = std::make_unique<CvodesIntegrator>(*this, options);
  }

  int state_size() const override { return kStateSize; }
  int sensitivity_count() const override { return 0; }
  int root_count() const override { return 5; }

  void CalcDerivatives(double, const double* x, double* dx) const override {
    const Vector2 acceleration = Acceleration(mode_, {x[2], x[3]}, nullptr);
    dx[0] = x[2];
    dx[1] = x[3];
    dx[2] = acceleration[0];
    dx[3] = acceleration[1];
  }
  void CalcStateJacobian(double, const double* x, double* jacobian) const override {
    // The field is affine in the rates: difference quotients are exact.
    for (int i = 0; i < 16; ++i) jacobian[i] = 0.0;
    jacobian[2 * 4 + 0] = 1.0;  // d(psi_L)/dt wrt psi_L'
    jacobian[3 * 4 + 1] = 1.0;
    const Vector2 base = Acceleration(mode_, {x[2], x[3]}, nullptr);
    for (int j = 0; j < 2; ++j) {
      Vector2 rate = {x[2], x[3]};
      rate[static_cast<std::size_t>(j)] += 1.0;
      const Vector2 shifted = Acceleration(mode_, rate, nullptr);
      jacobian[(2 + j) * 4 + 2] = shifted[0] - base[0];
      jacobian[(2 + j) * 4 + 3] = shifted[1] - base[1];
    }
  }
  void CalcSensitivityDerivative(double, const double*, int, const double*, double*) const override {}
  void CalcRoots(double, const double* x, double* g) const override {
    const Vector2 rate = {x[2], x[3]};
    double stuck_force = 0.0;
    int stuck_contact = -1;
    for (int i = 0; i < kContacts; ++i) {
      if (mode_[static_cast<std::size_t>(i)] == 0) stuck_contact = i;
    }
    const bool single_stuck = stuck_contact >= 0 && !AllStuck(mode_);
    if (single_stuck) Acceleration(mode_, rate, &stuck_force);
    for (int i = 0; i < kContacts; ++i) {
      g[i] = mode_[static_cast<std::size_t>(i)] != 0 ? Dot(kDirection[i], rate) : 1.0;
    }
    g[3] = single_stuck ? limit_[static_cast<std::size_t>(stuck_contact)] - stuck_force : 1.0;
    g[4] = single_stuck ? limit_[static_cast<std::size_t>(stuck_contact)] + stuck_force : 1.0;
  }

  void Reset(const CDrivePlantState& state) {
    state_ = state;
    switches_ = 0;
    mode_ = {0, 0, 0};
    DecideMode();
  }

  void Advance(double from, double to, const Vector2& torque) {
    torque_ = torque;
    DecideMode();
    if (AllStuck(mode_)) return;  // nothing moves while the torque is held
    double x[kStateSize] = {state_.angle[0], state_.angle[1], state_.rate[0], state_.rate[1]};
    integrator_->Restart(from, x, {}, false);
    int events = 0;
    while (integrator_->Advance(to, to)) {
      CopyState();
      ZeroFiredContactRates();
      if (++events > 1000) {
        throw IdentificationError(fmt::format("cdrive simulation: more than 1000 stick/slip switches in one period at "
                                              "t = {} s (chattering)", integrator_->time()));
      }
      ++switches_;
      // Contacts whose velocity reached zero are now candidates to stick.
      DecideMode();
      if (AllStuck(mode_)) return;
      const double now[kStateSize] = {state_.angle[0], state_.angle[1], state_.rate[0], state_.rate[1]};
      integrator_->Restart(integrator_->time(), now, {}, false);
    }
    CopyState();
  }

  const CDrivePlantState& state() const { return state_; }
  std::array<bool, 3> stuck() const { return {mode_[0] == 0, mode_[1] == 0, mode_[2] == 0}; }
  int switch_count() const { return switches_; }

 private:
  static bool AllStuck(const Mode& mode) { return mode[0] == 0 && mode[1] == 0 && mode[2] == 0; }

  // Acceleration in `mode`; for one stuck contact, its constraint force.
  Vector2 Acceleration(const Mode& mode, const Vector2& rate, double* stuck_force) const {
    if (AllStuck(mode)) return {0.0, 0.0};
    Vector2 force = {torque_[0] - damping_(0, 0) * rate[0] - damping_(0, 1) * rate[1],
                     torque_[1] - damping_(1, 0) * rate[0] - damping_(1, 1) * rate[1]};
    int stuck = -1;
    for (int i = 0; i < kContacts; ++i) {
      const int s = mode[static_cast<std::size_t>(i)];
      if (s == 0) {
        stuck = i;
        continue;
      }
      force[0] -= limit_[static_cast<std::size_t>(i)] * s * kDirection[i][0];
      force[1] -= limit_[static_cast<std::size_t>(i)] * s * kDirection[i][1];
    }
    const Vector2 free(inverse_(0, 0) * force[0] + inverse_(0, 1) * force[1],
                      inverse_(1, 0) * force[0] + inverse_(1, 1) * force[1]);
    if (stuck < 0) return free;
    const double* g = kDirection[stuck];
    const Vector2 inverse_g(inverse_(0, 0) * g[0] + inverse_(0, 1) * g[1], inverse_(1, 0) * g[0] + inverse_(1, 1) * g[1]);
    const double f = Dot(g, free) / Dot(g, inverse_g);
    if (stuck_force != nullptr) *stuck_force = f;
    return {free[0] - f * inverse_g[0], free[1] - f * inverse_g[1]};
  }

  bool Consistent(const Mode& mode, const Vector2& rate) const {
    if (AllStuck(mode)) {
      // Some collar force within [-eta, eta] must leave both motor forces within +-delta.
      const double low = std::max({torque_[0] - limit_[0], -torque_[1] - limit_[1], -limit_[2]});
      const double high = std::min({torque_[0] + limit_[0], -torque_[1] + limit_[1], limit_[2]});
      return low <= high;
    }
    double stuck_force = 0.0;
    const Vector2 acceleration = Acceleration(mode, rate, &stuck_force);
    for (int i = 0; i < kContacts; ++i) {
      const int s = mode[static_cast<std::size_t>(i)];
      if (s == 0) {
        if (std::abs(stuck_force) > limit_[static_cast<std::size_t>(i)]) return false;
      } else if (std::abs(Dot(kDirection[i], rate)) <= kZeroRate) {
        // Starting to slide from rest: it must accelerate in direction s.
        if (Dot(kDirection[i], acceleration) * s <= 0.0) return false;
      }
    }
    return true;
  }

  // Chooses the most-stuck consistent mode for the current state and torque.
  void DecideMode() {
    const Vector2 rate = state_.rate;
    std::array<std::array<int, 3>, kContacts> options{};
    std::array<int, kContacts> option_count{};
    for (int i = 0; i < kContacts; ++i) {
      const double v = Dot(kDirection[i], rate);
      auto& o = options[static_cast<std::size_t>(i)];
      auto& count = option_count[static_cast<std::size_t>(i)];
      if (std::abs(v) > kZeroRate) {
        o[0] = v > 0 ? 1 : -1;
        count = 1;
      } else {
        o = {0, 1, -1};  // stuck first
        count = 3;
      }
    }
    Mode best{};
    int best_stuck = -1;
    Mode fallback = {Signum(rate[0]) >= 0 ? 1 : -1, Signum(rate[1]) >= 0 ? 1 : -1,
                     Signum(rate[0] - rate[1]) >= 0 ? 1 : -1};
    for (int a = 0; a < option_count[0]; ++a) {
      for (int b = 0; b < option_count[1]; ++b) {
        for (int c = 0; c < option_count[2]; ++c) {
          const Mode mode = {options[0][static_cast<std::size_t>(a)], options[1][static_cast<std::size_t>(b)],
                             options[2][static_cast<std::size_t>(c)]};
          if (!AllowedStuckSet(mode) || !Consistent(mode, rate)) continue;
          const int stuck = (mode[0] == 0) + (mode[1] == 0) + (mode[2] == 0);
          if (stuck > best_stuck) {
            best = mode;
            best_stuck = stuck;
          }
        }
      }
    }
    if (best_stuck < 0) best = fallback;  // numerically at a boundary: slide
    mode_ = best;
    // Enforce the constraints of stuck contacts exactly.
    if (AllStuck(mode_)) {
      state_.rate = {0.0, 0.0};
    } else if (mode_[0] == 0) {
      state_.rate[0] = 0.0;
    } else if (mode_[1] == 0) {
      state_.rate[1] = 0.0;
    } else if (mode_[2] == 0) {
      const double mean = 0.5 * (state_.rate[0] + state_.rate[1]);
      state_.rate = {mean, mean};
    }
  }

  // The contacts whose velocity root fired are at rest: the root finder
  // places the crossing to about 100 ulp of t, so late in a long run (t of
  // several 100 s) the velocity left there exceeds kZeroRate and, taken as
  // sliding, flips the contact's direction at every event (chattering).
  // Two fired contacts leave both motors at rest (any two of the three
  // directions span the plane); one is projected out of the rates.
  void ZeroFiredContactRates() {
    const auto& fired = integrator_->root_directions();
    int count = 0, which = -1;
    for (int i = 0; i < kContacts; ++i) {
      if (fired[static_cast<std::size_t>(i)] != 0) {
        ++count;
        which = i;
      }
    }
    if (count >= 2) {
      state_.rate = {0.0, 0.0};
    } else if (count == 1) {
      const double* d = kDirection[which];
      const double along = Dot(d, state_.rate) / (d[0] * d[0] + d[1] * d[1]);
      state_.rate = {state_.rate[0] - along * d[0], state_.rate[1] - along * d[1]};
    }
  }

  void CopyState() {
    const double* x = integrator_->state();
    state_.angle = {x[0], x[1]};
    state_.rate = {x[2], x[3]};
    // A velocity that the root finder brought to (almost) zero is zero.
    for (int i = 0; i < 2; ++i) {
      if (std::abs(state_.rate[static_cast<std::size_t>(i)]) <= kZeroRate) state_.rate[static_cast<std::size_t>(i)] = 0.0;
    }
  }

  CDriveParameters params_;
  Matrix2 inverse_ = Matrix2::Zero();
  Matrix2 damping_ = Matrix2::Zero();
  std::array<double, kContacts> limit_{};
  std::unique_ptr<CvodesIntegrator> integrator_;
  CDrivePlantState state_;
  Vector2 torque_ = Vector2::Zero();
  Mode mode_{};
  int switches_ = 0;
};

CDrivePlant::CDrivePlant(const CDriveParameters& params) : system_(std::make_unique<System>(params)) {}
CDrivePlant::~CDrivePlant() = default;
void CDrivePlant::Reset(const CDrivePlantState& state) { system_->Reset(state); }
void CDrivePlant::Advance(double from, double to, const Vector2& torque) { system_->Advance(from, to, torque); }
const CDrivePlantState& CDrivePlant::state() const { return system_->state(); }
std::array<bool, 3> CDrivePlant::stuck() const { return system_->stuck(); }
int CDrivePlant::switch_count() const { return system_->switch_count(); }

}  // namespace driveid
