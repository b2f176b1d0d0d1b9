// The two masses' inertias (docs/models.md#elastic-joint): J_m theta_m''
// on the motor, J_l theta_l'' on the link, both referred to the link side
// (J_m is n^2 times the rotor's). The mass matrix is diagonal: no term
// couples the accelerations.
#include <memory>

#include "models/joint.h"
#include "models/joint_term.h"

namespace driveid {
namespace {

class JointInertiaTerm final : public JointModelTerm {
 public:
  std::string name() const override { return "inertia"; }
  std::vector<JointRow> Rows() const override {
    return {{Spec("motor_inertia", "J_m", "kg m^2", "motor inertia, link side").Fit("joint").FreeByDefault(),
             &JointSection::motor_inertia, &JointParameters::motor_inertia},
            {Spec("link_inertia", "J_l", "kg m^2", "link inertia").Fit("joint").FreeByDefault(),
             &JointSection::link_inertia, &JointParameters::link_inertia}};
  }
  JointRowKind Kind(std::size_t) const override { return JointRowKind::kLinear; }
  void Columns(const JointMotion& x, JointColumn* out) const override {
    out[0] = {x.motor_acceleration, 0.0, 0.0};
    out[1] = {0.0, x.link_acceleration, 0.0};
  }
};

}  // namespace

DRIVEID_JOINT_TERM(inertia, JointInertiaTerm)

}  // namespace driveid
