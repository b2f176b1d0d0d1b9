// The motor's friction to ground (docs/models.md#elastic-joint):
// b_m theta_m' + c_m sgn(theta_m'), link side (n^2 and n times the rotor's
// b and the motor's c). The simulators hold the Coulomb part through stick
// (sim/joint_simulator.h).
#include <memory>

#include "models/joint.h"
#include "models/joint_term.h"

namespace driveid {
namespace {

class JointMotorFrictionTerm final : public JointModelTerm {
 public:
  std::string name() const override { return "motor friction"; }
  std::vector<JointRow> Rows() const override {
    return {{Spec("motor_viscous", "b_m", "N m s/rad", "motor-side viscous friction").Fit("joint").FreeByDefault(),
             &JointSection::motor_viscous, &JointParameters::motor_viscous},
            {Spec("motor_coulomb", "c_m", "N m", "motor-side Coulomb friction").Fit("joint").FreeByDefault(),
             &JointSection::motor_coulomb, &JointParameters::motor_coulomb}};
  }
  JointRowKind Kind(std::size_t row) const override { return row == 0 ? JointRowKind::kLinear : JointRowKind::kDry; }
  void Columns(const JointMotion& x, JointColumn* out) const override {
    out[0] = {x.motor_rate, 0.0, 0.0};
    out[1] = {static_cast<double>((x.motor_rate > 0.0) - (x.motor_rate < 0.0)), 0.0, 0.0};
  }
};

}  // namespace

DRIVEID_JOINT_TERM(motor_friction, JointMotorFrictionTerm)

}  // namespace driveid
