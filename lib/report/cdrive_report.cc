#include "report/cdrive_report.h"

#include <cmath>

#include <fmt/format.h>

#include "report/fit_summary.h"

namespace driveid {
namespace {

// Seed 001 Table I.
struct PaperValue {
  const char* key;
  double value;
};
constexpr PaperValue kTableOne[] = {{"beta", 0.002655}, {"gamma", 0.004333}, {"delta", 0.1086}, {"eta", 0.1501}};

double Lookup(const std::vector<ParameterEstimate>& estimates, const std::string& name) {
  for (const auto& e : estimates) {
    if (e.name == name) return e.standard_error;
  }
  return std::nan("");
}

bool IsGiven(double value) { return value == value; }

bool InertiaGiven(const CDriveParameters& p) {
  return IsGiven(p.hub_inertia) && IsGiven(p.collar_inertia) && IsGiven(p.collar_mass);
}

std::string Value(double value, double standard_error) {
  if (!IsGiven(value)) return "-";
  if (IsGiven(standard_error)) return fmt::format("{:.6g} +- {:.2g}", value, standard_error);
  return fmt::format("{:.6g}", value);
}

}  // namespace

std::string FormatCDriveReport(const CDriveSection& cdrive, const std::optional<CDriveControlSection>& control,
                               const std::vector<ParameterEstimate>& estimates, const std::string& source) {
  const CDriveParameters p = ModelValuesOrNaN(CDriveParameterTable(), cdrive);
  const Matrix2 j = CalcCDriveJacobian(p.lead);
  const Matrix2 inverse = CalcCDriveJacobianInverse(p.lead);
  std::string out = fmt::format("C-drive from {} (seed 001; docs/models.md#c-drive), lead p = {} m\n\n", source, p.lead);
  out += "kinematics w = (u, v) = J psi, v = p theta / (2 pi):\n";
  out += fmt::format("  J    = p/(4 pi) [[1, -1], [1, 1]]    = [[{:.6g}, {:.6g}], [{:.6g}, {:.6g}]] m/rad\n", j(0, 0), j(0, 1),
                     j(1, 0), j(1, 1));
  out += fmt::format("  J^-1 = (2 pi/p) [[1, 1], [-1, 1]]    = [[{:.6g}, {:.6g}], [{:.6g}, {:.6g}]] rad/m "
                     "(the seed prints pi/p, which gives J J^-1 = 1/2)\n",
                     inverse(0, 0), inverse(0, 1), inverse(1, 0), inverse(1, 1));
  out += fmt::format("  J'J  = p^2/(8 pi^2) 1 = {:.6g} 1 m^2/rad^2: isotropic, condition number 1\n",
                     p.lead * p.lead / (8 * M_PI * M_PI));
  if (InertiaGiven(p)) {
    const double a = CalcInertiaDiagonal(p), b = CalcInertiaOffDiagonal(p);
    const double isotropic_collar = std::pow(p.lead / (2 * M_PI), 2) * p.collar_mass;
    out += "\ninertia (eq. 17): M = [[a, b], [b, a]]\n";
    out += fmt::format("  a = I_h + I_c/4 + p^2 m/(16 pi^2) = {:.6g} kg m^2\n", a);
    out += fmt::format("  b = I_c/4 - p^2 m/(16 pi^2)       = {:.6g} kg m^2\n", b);
    out += fmt::format("  eigenvalues a + b = {:.6g} (rotation), a - b = {:.6g} (translation); condition number {:.4g}\n",
                       a + b, a - b, std::max(a + b, a - b) / std::min(a + b, a - b));
    out += fmt::format("  isotropic (M proportional to 1, eq. 18) needs I_c = (p/2pi)^2 m = {:.4g} kg m^2; here I_c = "
                       "{:.4g}: {}\n",
                       isotropic_collar, p.collar_inertia,
                       std::abs(b) <= 1e-3 * a ? "isotropic" : "not isotropic, the motors are coupled");
  } else {
    out += "\ninertia: I_h, I_c, m not all given\n";
  }
  out += "\ndissipation (Table I):\n";
  out += fmt::format("  {:<18} {:<34} {:<34}\n", "part", "viscous [N m s/rad]", "Coulomb [N m]");
  out += fmt::format("  {:<18} {:<34} {:<34}\n", "rotational parts",
                     "beta = " + Value(p.viscous_motor, Lookup(estimates, "beta")),
                     "delta = " + Value(p.coulomb_motor, Lookup(estimates, "delta")));
  out += fmt::format("  {:<18} {:<34} {:<34}\n", "collar",
                     "gamma = " + Value(p.viscous_collar, Lookup(estimates, "gamma")),
                     "eta = " + Value(p.coulomb_collar, Lookup(estimates, "eta")));
  out += "  paper Table I:     beta = 0.002655, gamma = 0.004333, delta = 0.1086, eta = 0.1501\n";
  const double values[] = {p.viscous_motor, p.viscous_collar, p.coulomb_motor, p.coulomb_collar};
  std::string deviations;
  for (int i = 0; i < 4; ++i) {
    if (!IsGiven(values[i])) continue;
    deviations += fmt::format("{}{} {:+.2f} %", deviations.empty() ? "" : ", ", kTableOne[i].key,
                              100.0 * (values[i] / kTableOne[i].value - 1.0));
  }
  if (!deviations.empty()) out += "  vs Table I:       " + deviations + "\n";
  if (control) {
    const CDriveControlSettings c = MakeControlSettings(*control);
    out += fmt::format("\ncontroller: {} at {} Hz, K_P = {} N m/rad, K_I = {} ({}), dead zone {} rad/s, rate limit {} /s\n",
                       ControlLawName(c.law), 1.0 / c.sample_time, c.proportional_gain, c.second_gain,
                       c.law == ControlLaw::kPD ? "read as a derivative gain, N m s/rad"
                                                : "integral gain, N m/(rad s)",
                       c.dead_zone, c.rate_limit);
  }
  return out;
}

Json CDriveReportJson(const CDriveSection& cdrive, const std::vector<ParameterEstimate>& estimates,
                      const std::string& source) {
  const CDriveParameters p = ModelValuesOrNaN(CDriveParameterTable(), cdrive);
  const Matrix2 j = CalcCDriveJacobian(p.lead), inverse = CalcCDriveJacobianInverse(p.lead);
  Json out;
  out["source"] = source;
  out["lead"] = p.lead;
  out["jacobian"] = {j(0, 0), j(0, 1), j(1, 0), j(1, 1)};
  out["jacobian_inverse"] = {inverse(0, 0), inverse(0, 1), inverse(1, 0), inverse(1, 1)};
  out["jtj"] = p.lead * p.lead / (8 * M_PI * M_PI);
  if (InertiaGiven(p)) {
    out["a"] = CalcInertiaDiagonal(p);
    out["b"] = CalcInertiaOffDiagonal(p);
  }
  const double values[] = {p.viscous_motor, p.viscous_collar, p.coulomb_motor, p.coulomb_collar};
  out["dissipation"] = Json::object();
  for (int i = 0; i < 4; ++i) {
    out["dissipation"][kTableOne[i].key] = {{"value", IsGiven(values[i]) ? Json(values[i]) : Json(nullptr)},
                                            {"std", Lookup(estimates, kTableOne[i].key)},
                                            {"table_one", kTableOne[i].value}};
  }
  return out;
}

}  // namespace driveid
