// The Stribeck breakaway excess (docs/models.md#axis):
//   F = tau_s exp(-(q'/v_s)^2) m,
// m the direction of motion: at rest the axis breaks away at
// tau_c + tau_s, moving the excess fades over the Stribeck velocity v_s.
// Nonlinear in v_s, so only the output-error fit estimates it; v_s has a
// plateau (v_s -> infinity: the excess joins the Coulomb term) the fit must
// start around. Neither simulators' files nor WPILib's classes hold it.
#include <cmath>

#include <fmt/format.h>

#include "core/errors.h"
#include "models/axis_term.h"

namespace driveid {
namespace {

class StribeckTerm final : public AxisTerm {
 public:
  std::string name() const override { return "Stribeck"; }
  std::vector<AxisRow> Rows() const override {
    return {{Spec("stribeck", "tau_s", "N m", "Stribeck breakaway excess over Coulomb (output error only)").Fit("axis"),
             nullptr, nullptr},
            {Spec("stribeck_velocity", "v_s", "rad/s", "Stribeck velocity: the excess fades as exp(-(q'/v_s)^2)")
                 .Fit("axis"),
             nullptr, nullptr}};
  }
  bool linear() const override { return false; }
  // exp(-(v/v_s)^2), the factor of tau_s m.
  static double Fade(const double* p, double v) {
    const double r = v / p[1];
    return std::exp(-r * r);
  }
  static bool Active(const double* p) { return p[0] != 0.0 && p[1] > 0.0; }
  double Force(const double* p, double, double v, int m) const override {
    if (!Active(p) || m == 0) return 0.0;
    return p[0] * m * Fade(p, v);
  }
  double ForceRateSlope(const double* p, double, double v, int m) const override {
    if (!Active(p)) return 0.0;
    return p[0] * m * Fade(p, v) * (-2.0 * v / (p[1] * p[1]));
  }
  double ForceParameterSlope(std::size_t i, const double* p, double, double v, int m) const override {
    if (!Active(p)) return 0.0;
    const double e = Fade(p, v);
    // d/d tau_s and d/d v_s of tau_s m exp(-(v/v_s)^2).
    return i == 0 ? m * e : p[0] * m * e * 2.0 * v * v / (p[1] * p[1] * p[1]);
  }
  bool mode_affine() const override { return false; }
  bool Present(const double* p) const override { return p[0] != 0.0; }
  void ForceBound(const double* p, double* constant, double* per_rate) const override {
    *constant = std::abs(p[0]);
    *per_rate = 0.0;
  }
  void CheckFitStart(const double* p, const std::vector<bool>& free) const override {
    if ((free[0] || p[0] != 0.0) && !(p[1] > 0.0)) {
      throw InputError("‹params›: axis.stribeck_velocity must be > 0 (a start value if free) with the Stribeck term");
    }
    if (free[0] && p[0] == 0.0) {
      throw InputError("‹free› stribeck: give a start value > 0 in ‹params› (axis.stribeck): at 0 the fit cannot "
                       "tell which way to move stribeck_velocity");
    }
  }
  int scale_row() const override { return 1; }
  std::string ExportNote(AxisExportTarget target) const override {
    return target == AxisExportTarget::kWpilib
               ? "The Stribeck term is not representable in WPILib's feed-forward classes."
               : "Stribeck breakaway term: not representable, left out";
  }
};

}  // namespace

DRIVEID_AXIS_TERM(stribeck, StribeckTerm)

}  // namespace driveid
