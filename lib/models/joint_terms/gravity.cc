// Gravity on the link (docs/models.md#elastic-joint): a link whose centre
// of mass lies off its axis in a vertical plane takes
// g_c cos theta_l + g_s sin theta_l [N m] (m g r resolved along the angle
// the encoder calls zero). Linear in g_c, g_s but not in the motion: the
// frequency response leaves it out (linear about rest) and the simulator
// integrates where it is present.
#include <cmath>
#include <memory>

#include "models/joint.h"
#include "models/joint_term.h"

namespace driveid {
namespace {

class JointGravityTerm final : public JointModelTerm {
 public:
  std::string name() const override { return "gravity"; }
  std::vector<JointRow> Rows() const override {
    return {{Spec("gravity_cos", "g_c", "N m", "gravity torque amplitude of cos q_link").Unbounded().Fit("joint"),
             &JointSection::gravity_cos, &JointParameters::gravity_cos},
            {Spec("gravity_sin", "g_s", "N m", "gravity torque amplitude of sin q_link").Unbounded().Fit("joint"),
             &JointSection::gravity_sin, &JointParameters::gravity_sin}};
  }
  JointRowKind Kind(std::size_t) const override { return JointRowKind::kAngle; }
  void Columns(const JointMotion& x, JointColumn* out) const override {
    out[0] = {0.0, std::cos(x.link_angle), 0.0};
    out[1] = {0.0, std::sin(x.link_angle), 0.0};
  }
};

}  // namespace

DRIVEID_JOINT_TERM(gravity, JointGravityTerm)

}  // namespace driveid
