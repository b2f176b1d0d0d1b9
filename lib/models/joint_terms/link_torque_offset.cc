// The offset of a logged shaft torque (docs/models.md#elastic-joint):
// tau_link = k D + d D' + tau_l0, with tau_l0 the sensor's bias plus k
// times the unknown initial twist of angles integrated from speeds. It is
// the sensor's, not a force on either mass: exports leave it out.
#include <memory>

#include "models/joint.h"
#include "models/joint_term.h"

namespace driveid {
namespace {

class JointLinkTorqueOffsetTerm final : public JointModelTerm {
 public:
  std::string name() const override { return "shaft-torque offset"; }
  std::vector<JointRow> Rows() const override {
    return {{Spec("link_torque_offset", "tau_l0", "N m",
                  "offset of a logged shaft torque tau_link (sensor bias + k x initial twist)")
                 .Unbounded()
                 .Fit("joint"),
             &JointSection::link_torque_offset, &JointParameters::link_torque_offset}};
  }
  JointRowKind Kind(std::size_t) const override { return JointRowKind::kSensor; }
  void Columns(const JointMotion&, JointColumn* out) const override { out[0] = {0.0, 0.0, 1.0}; }
};

}  // namespace

DRIVEID_JOINT_TERM(link_torque_offset, JointLinkTorqueOffsetTerm)

}  // namespace driveid
