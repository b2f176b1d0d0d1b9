// Viscous friction per direction (docs/models.md#axis):
// F = b+ max(q', 0) + b- min(q', 0) in a direction of motion (b- a
// magnitude). It replaces the plain viscous term when fitted.
#include <algorithm>
#include <cmath>

#include "models/axis_term.h"

namespace driveid {
namespace {

class DirectionalViscousTerm final : public AxisTerm {
 public:
  std::string name() const override { return "viscous per direction"; }
  std::vector<AxisRow> Rows() const override {
    return {{Spec("viscous_pos", "b+", "N m s/rad", "viscous friction moving forward").Fit("axis"),
             &AxisSection::viscous_pos, &AxisParameters::viscous_pos},
            {Spec("viscous_neg", "b-", "N m s/rad", "viscous friction moving backward").Fit("axis"),
             &AxisSection::viscous_neg, &AxisParameters::viscous_neg}};
  }
  bool linear() const override { return true; }
  void Regressors(double, double v, double, int m, double* phi) const override {
    const double forward = m > 0 ? 1.0 : 0.0, backward = m < 0 ? 1.0 : 0.0;
    phi[0] = forward * v;
    phi[1] = backward * v;
  }
  void RegressorSlopes(double, double, int m, double* d_dq, double* d_dv) const override {
    d_dq[0] = d_dq[1] = 0.0;
    d_dv[0] = m > 0 ? 1.0 : 0.0;
    d_dv[1] = m < 0 ? 1.0 : 0.0;
  }
  void ForceBound(const double* p, double* constant, double* per_rate) const override {
    *constant = 0.0;
    *per_rate = std::max(std::abs(p[0]), std::abs(p[1]));
  }
};

}  // namespace

DRIVEID_AXIS_TERM(directional_viscous, DirectionalViscousTerm)

}  // namespace driveid
