// Coulomb friction tau_c [N m or N]: F = tau_c sgn(q'), sgn(0) = 0; at rest
// the axis sticks while the static torque stays within it
// (docs/models.md#axis, sim/axis_simulator.h).
#include <cmath>

#include "models/axis_term.h"

namespace driveid {
namespace {

class CoulombTerm final : public AxisTerm {
 public:
  std::string name() const override { return "Coulomb"; }
  std::vector<AxisRow> Rows() const override {
    return {{Spec("coulomb", "tau_c", "N m", "Coulomb friction").Fit("axis").FreeByDefault(), &AxisSection::coulomb,
             &AxisParameters::coulomb}};
  }
  bool linear() const override { return true; }
  void Regressors(double, double, double, int m, double* phi) const override {
    const double forward = m > 0 ? 1.0 : 0.0, backward = m < 0 ? 1.0 : 0.0;
    phi[0] = forward - backward;
  }
  void RegressorSlopes(double, double, int, double* d_dq, double* d_dv) const override { d_dq[0] = d_dv[0] = 0.0; }
  void ForceBound(const double* p, double* constant, double* per_rate) const override {
    *constant = std::abs(p[0]);
    *per_rate = 0.0;
  }
};

}  // namespace

DRIVEID_AXIS_TERM(coulomb, CoulombTerm)

}  // namespace driveid
