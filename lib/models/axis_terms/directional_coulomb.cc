// Coulomb friction per direction (docs/models.md#axis):
// F = tau_c+ [q' > 0] - tau_c- [q' < 0], tau_c- a magnitude. It replaces
// the plain Coulomb term when fitted (models/axis.h AxisReplacedBy).
#include <algorithm>
#include <cmath>

#include "models/axis_term.h"

namespace driveid {
namespace {

class DirectionalCoulombTerm final : public AxisTerm {
 public:
  std::string name() const override { return "Coulomb per direction"; }
  std::vector<AxisRow> Rows() const override {
    return {{Spec("coulomb_pos", "tau_c+", "N m", "Coulomb friction moving forward (q' > 0)").Fit("axis"),
             &AxisSection::coulomb_pos, &AxisParameters::coulomb_pos},
            {Spec("coulomb_neg", "tau_c-", "N m", "Coulomb friction moving backward (magnitude, q' < 0)").Fit("axis"),
             &AxisSection::coulomb_neg, &AxisParameters::coulomb_neg}};
  }
  bool linear() const override { return true; }
  void Regressors(double, double, double, int m, double* phi) const override {
    const double forward = m > 0 ? 1.0 : 0.0, backward = m < 0 ? 1.0 : 0.0;
    phi[0] = forward;
    phi[1] = -backward;
  }
  void RegressorSlopes(double, double, int, double* d_dq, double* d_dv) const override {
    d_dq[0] = d_dq[1] = d_dv[0] = d_dv[1] = 0.0;
  }
  void ForceBound(const double* p, double* constant, double* per_rate) const override {
    *constant = std::max(std::abs(p[0]), std::abs(p[1]));
    *per_rate = 0.0;
  }
};

}  // namespace

DRIVEID_AXIS_TERM(directional_coulomb, DirectionalCoulombTerm)

}  // namespace driveid
