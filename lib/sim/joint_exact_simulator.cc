// The joint simulator's exact path (sim/joint_simulator.h): without gravity
// the joint is linear within a friction mode, x' = A x + c + b u with u held
// over a sample; this file gives the fields A, c, b of each mode, their
// derivatives and the motor's static torque to the exact simulation of
// sim/switched_linear_exact.h, which solves each interval by matrix
// exponentials and handles the stick/slip events.
#include <cmath>
#include <vector>

#include "sim/joint_exact_simulator.h"
#include "sim/joint_response.h"
#include "sim/switched_linear_exact.h"

namespace driveid {
namespace {
constexpr int kThetaL = 2, kOmegaL = 3;
constexpr long kSwitchesPerSample = 4, kSwitchBudgetConstant = 2000;

using Vector4 = Eigen::Vector4d;

// The linear field of one mode and its parameter derivatives.
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

// The joint as the exact simulation's model (static torque N = u - k D + d omega_l - tau_0).
class JointLinearModel final : public SwitchedLinearModel {
 public:
  JointLinearModel(const JointParameters& p, const std::vector<int>& terms) : p_(p), terms_(terms) {}
  ModeField Field(int mode) const override { return driveid::Field(p_, mode); }
  ModeField FieldDerivative(int mode, int j) const override {
    return driveid::FieldDerivative(p_, mode, terms_[static_cast<std::size_t>(j)]);
  }
  int InitialStateIndex(int j) const override { return driveid::InitialStateIndex(terms_[static_cast<std::size_t>(j)]); }
  double StaticTorque(const Vector4& x, double u) const override {
    return u - p_.stiffness * (x(0) - x(kThetaL)) + p_.damping * x(kOmegaL) - p_.offset;
  }
  double StaticTorqueRate(const Vector4& dx) const override {
    return -p_.stiffness * (dx(0) - dx(kThetaL)) + p_.damping * dx(kOmegaL);
  }
  double Coulomb() const override { return p_.motor_coulomb; }

 private:
  const JointParameters& p_;
  const std::vector<int>& terms_;
};

}  // namespace

class JointExactSimulator::Impl {
 public:
  explicit Impl(std::vector<int> terms) : terms_(std::move(terms)) {}

  void Simulate(const JointParameters& p, const std::vector<double>& time, const std::vector<double>& torque,
                const std::array<double, 4>& x0, bool with_sensitivities, JointStateResponse* out) {
    const std::size_t samples = time.size(), np = terms_.size();
    const bool sensitivities = with_sensitivities && np > 0;
    out->state.assign(samples * 4, 0.0);
    out->sensitivity.assign(sensitivities ? samples * np * 4 : 0, 0.0);
    out->mode.assign(samples, 0);
    out->switch_count = 0;
    if (samples == 0) return;
    const JointLinearModel model(p, terms_);
    const long budget = kSwitchBudgetConstant + kSwitchesPerSample * static_cast<long>(samples);
    run_.Start(model, Vector4(x0[0], x0[1], x0[2], x0[3]), torque[0], sensitivities ? static_cast<int>(np) : 0,
               budget);
    Record(0, out);
    for (std::size_t k = 0; k + 1 < samples; ++k) {
      run_.Advance(time[k + 1] - time[k], torque[k], time[k]);
      Record(k + 1, out);
    }
    out->switch_count = static_cast<int>(run_.switches());  // at most the budget
  }

 private:
  void Record(std::size_t k, JointStateResponse* out) const {
    const Vector4& x = run_.state();
    for (int i = 0; i < 4; ++i) out->state[4 * k + static_cast<std::size_t>(i)] = x(i);
    out->mode[k] = run_.mode();
    const auto& s = run_.sensitivities();
    const std::size_t np = s.size();
    for (std::size_t j = 0; j < np; ++j) {
      for (int i = 0; i < 4; ++i) out->sensitivity[(k * np + j) * 4 + static_cast<std::size_t>(i)] = s[j](i);
    }
  }

  std::vector<int> terms_;
  SwitchedLinearExact run_;
};

JointExactSimulator::JointExactSimulator(std::vector<int> terms) : impl_(std::make_unique<Impl>(std::move(terms))) {}

JointExactSimulator::~JointExactSimulator() = default;

void JointExactSimulator::Simulate(const JointParameters& p, const std::vector<double>& time,
                                   const std::vector<double>& motor_torque, const std::array<double, 4>& x0,
                                   bool with_sensitivities, JointStateResponse* response) {
  impl_->Simulate(p, time, motor_torque, x0, with_sensitivities, response);
}

}  // namespace driveid
