// Viscous friction b [N m s/rad or N s/m]: F = b q' (docs/models.md#axis).
#include <cmath>

#include "models/axis_term.h"

namespace driveid {
namespace {

class ViscousTerm final : public AxisTerm {
 public:
  std::string name() const override { return "viscous"; }
  std::vector<AxisRow> Rows() const override {
    return {{Spec("viscous", "b", "N m s/rad", "viscous friction").Fit("axis").FreeByDefault(), &AxisSection::viscous,
             &AxisParameters::viscous}};
  }
  bool linear() const override { return true; }
  void Regressors(double, double v, double, int, double* phi) const override { phi[0] = v; }
  void RegressorSlopes(double, double, int, double* d_dq, double* d_dv) const override {
    d_dq[0] = 0.0;
    d_dv[0] = 1.0;
  }
  void ForceBound(const double* p, double* constant, double* per_rate) const override {
    *constant = 0.0;
    *per_rate = std::abs(p[0]);
  }
};

}  // namespace

DRIVEID_AXIS_TERM(viscous, ViscousTerm)

}  // namespace driveid
