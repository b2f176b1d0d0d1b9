// The elastic element's stiffness (docs/models.md#elastic-joint): with the
// deflection D = theta_m - theta_l it takes k D from the motor and gives it
// to the link (-k D taken), and a shaft-torque sensor in the element reads
// k D. Its columns sum to zero over both masses: the spring drops out of the
// total equation, which is why that equation identifies the friction and
// inertias whatever the stiffness.
#include <memory>

#include "models/joint.h"
#include "models/joint_term.h"

namespace driveid {
namespace {

class JointSpringTerm final : public JointModelTerm {
 public:
  std::string name() const override { return "spring"; }
  std::vector<JointRow> Rows() const override {
    return {{Spec("stiffness", "k", "N m/rad", "joint stiffness").Fit("joint").FreeByDefault(),
             &JointSection::stiffness, &JointParameters::stiffness}};
  }
  JointRowKind Kind(std::size_t) const override { return JointRowKind::kLinear; }
  void Columns(const JointMotion& x, JointColumn* out) const override {
    const double deflection = x.motor_angle - x.link_angle;
    out[0] = {deflection, -deflection, deflection};
  }
};

}  // namespace

DRIVEID_JOINT_TERM(spring, JointSpringTerm)

}  // namespace driveid
