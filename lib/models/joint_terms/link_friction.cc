// The link's friction to ground (docs/models.md#elastic-joint), behind the
// elastic element: b_l theta_l' + c_l sgn(theta_l'). Only the total equation
// sees it (the motor's does not reach past the spring). The output-error
// simulation does not hold the link's Coulomb part and refuses it by name
// (fit/joint/joint_oe_fit.h).
#include <memory>

#include "models/joint.h"
#include "models/joint_term.h"

namespace driveid {
namespace {

class JointLinkFrictionTerm final : public JointModelTerm {
 public:
  std::string name() const override { return "link friction"; }
  std::vector<JointRow> Rows() const override {
    return {{Spec("link_viscous", "b_l", "N m s/rad", "link-side viscous friction").Fit("joint").FreeByDefault(),
             &JointSection::link_viscous, &JointParameters::link_viscous},
            {Spec("link_coulomb", "c_l", "N m", "link-side Coulomb friction").Fit("joint").FreeByDefault(),
             &JointSection::link_coulomb, &JointParameters::link_coulomb}};
  }
  JointRowKind Kind(std::size_t row) const override { return row == 0 ? JointRowKind::kLinear : JointRowKind::kDry; }
  void Columns(const JointMotion& x, JointColumn* out) const override {
    out[0] = {0.0, x.link_rate, 0.0};
    out[1] = {0.0, static_cast<double>((x.link_rate > 0.0) - (x.link_rate < 0.0)), 0.0};
  }
};

}  // namespace

DRIVEID_JOINT_TERM(link_friction, JointLinkFrictionTerm)

}  // namespace driveid
