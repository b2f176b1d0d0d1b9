// A constant offset tau_0 [N m or N] (docs/models.md#axis): a drive's
// current offset, or on a linear axis its weight.
#include <cmath>

#include "models/axis_term.h"

namespace driveid {
namespace {

class OffsetTerm final : public AxisTerm {
 public:
  std::string name() const override { return "offset"; }
  std::vector<AxisRow> Rows() const override {
    return {{Spec("offset", "tau_0", "N m", "constant offset").Unbounded().Fit("axis").FreeByDefault(),
             &AxisSection::offset, &AxisParameters::offset}};
  }
  bool linear() const override { return true; }
  void Regressors(double, double, double, int, double* phi) const override { phi[0] = 1.0; }
  void RegressorSlopes(double, double, int, double* d_dq, double* d_dv) const override { d_dq[0] = d_dv[0] = 0.0; }
  void ForceBound(const double* p, double* constant, double* per_rate) const override {
    *constant = std::abs(p[0]);
    *per_rate = 0.0;
  }
};

}  // namespace

DRIVEID_AXIS_TERM(offset, OffsetTerm)

}  // namespace driveid
