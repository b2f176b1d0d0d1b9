// A constant torque on the motor side (docs/models.md#elastic-joint): the
// drive's current-sensor offset or a constant load, tau_0 [N m]. It and the
// Coulomb friction separate only with motion in both directions.
#include <memory>

#include "models/joint.h"
#include "models/joint_term.h"

namespace driveid {
namespace {

class JointOffsetTerm final : public JointModelTerm {
 public:
  std::string name() const override { return "offset"; }
  std::vector<JointRow> Rows() const override {
    return {{Spec("offset", "tau_0", "N m", "constant torque offset (motor side)").Unbounded().Fit("joint").FreeByDefault(),
             &JointSection::offset, &JointParameters::offset}};
  }
  JointRowKind Kind(std::size_t) const override { return JointRowKind::kConstant; }
  void Columns(const JointMotion&, JointColumn* out) const override { out[0] = {1.0, 0.0, 0.0}; }
};

}  // namespace

DRIVEID_JOINT_TERM(offset, JointOffsetTerm)

}  // namespace driveid
