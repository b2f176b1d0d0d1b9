// The elastic element's damping (docs/models.md#elastic-joint): d D', with
// D' = theta_m' - theta_l' the deflection rate, taken from the motor, given
// to the link, and read by a shaft-torque sensor with the spring's k D.
// Structural damping of a gear or belt; the masses' own friction to ground
// is the friction terms'.
#include <memory>

#include "models/joint.h"
#include "models/joint_term.h"

namespace driveid {
namespace {

class JointDamperTerm final : public JointModelTerm {
 public:
  std::string name() const override { return "damper"; }
  std::vector<JointRow> Rows() const override {
    return {{Spec("damping", "d", "N m s/rad", "joint damping (of the spring)").Fit("joint").FreeByDefault(),
             &JointSection::damping, &JointParameters::damping}};
  }
  JointRowKind Kind(std::size_t) const override { return JointRowKind::kLinear; }
  void Columns(const JointMotion& x, JointColumn* out) const override {
    const double deflection_rate = x.motor_rate - x.link_rate;
    out[0] = {deflection_rate, -deflection_rate, deflection_rate};
  }
};

}  // namespace

DRIVEID_JOINT_TERM(damper, JointDamperTerm)

}  // namespace driveid
