// Gravity on a rotary joint whose other joints stand still
// (docs/models.md#axis): F = g_c cos q + g_s sin q = A cos(q - phi), q in
// rad. It depends on q, so the simulator integrates where it is present.
#include <cmath>

#include "models/axis_term.h"

namespace driveid {
namespace {

class GravityTerm final : public AxisTerm {
 public:
  std::string name() const override { return "gravity"; }
  std::vector<AxisRow> Rows() const override {
    return {{Spec("gravity_cos", "g_c", "N m", "gravity torque amplitude of cos q (q in rad)").Unbounded().Fit("axis"),
             &AxisSection::gravity_cos, &AxisParameters::gravity_cos},
            {Spec("gravity_sin", "g_s", "N m", "gravity torque amplitude of sin q (q in rad)").Unbounded().Fit("axis"),
             &AxisSection::gravity_sin, &AxisParameters::gravity_sin}};
  }
  bool linear() const override { return true; }
  void Regressors(double q, double, double, int, double* phi) const override {
    phi[0] = std::cos(q);
    phi[1] = std::sin(q);
  }
  void RegressorSlopes(double q, double, int, double* d_dq, double* d_dv) const override {
    d_dq[0] = -std::sin(q);
    d_dq[1] = std::cos(q);
    d_dv[0] = d_dv[1] = 0.0;
  }
  bool mode_affine() const override { return false; }
  void ForceBound(const double* p, double* constant, double* per_rate) const override {
    *constant = std::hypot(p[0], p[1]);
    *per_rate = 0.0;
  }
};

}  // namespace

DRIVEID_AXIS_TERM(gravity, GravityTerm)

}  // namespace driveid
