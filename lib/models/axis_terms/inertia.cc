// Inertia J [kg m^2 or kg]: F = J q'' (docs/models.md#axis). The
// simulator divides the other terms' forces by it; it is never 0 there.
#include "models/axis_term.h"

namespace driveid {
namespace {

class InertiaTerm final : public AxisTerm {
 public:
  std::string name() const override { return "inertia"; }
  std::vector<AxisRow> Rows() const override {
    return {{Spec("inertia", "J", "kg m^2", "inertia").Fit("axis").FreeByDefault(), &AxisSection::inertia,
             &AxisParameters::inertia}};
  }
  bool linear() const override { return true; }
  void Regressors(double, double, double a, int, double* phi) const override { phi[0] = a; }
  void RegressorSlopes(double, double, int, double* d_dq, double* d_dv) const override { d_dq[0] = d_dv[0] = 0.0; }
};

}  // namespace

DRIVEID_AXIS_TERM(inertia, InertiaTerm)

}  // namespace driveid
