#include "report/cdrive_report.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace driveid {
namespace {

// Seed 001 Table I, in the order the report lists the dissipation parameters.
struct PaperValue {
  double CDriveParameters::*member;
  double value;
};
constexpr PaperValue kTableOne[] = {{&CDriveParameters::viscous_motor, 0.002655},
                                    {&CDriveParameters::viscous_collar, 0.004333},
                                    {&CDriveParameters::coulomb_motor, 0.1086},
                                    {&CDriveParameters::coulomb_collar, 0.1501}};

std::optional<double> StandardError(const std::vector<ParameterEstimate>& estimates, const std::string& name) {
  for (const auto& e : estimates) {
    if (e.name == name) return e.standard_error;
  }
  return std::nullopt;
}

std::string Value(const CDriveReport::Dissipation& d) {
  if (!d.value) return "-";
  if (d.standard_error) return fmt::format("{:.6g} +- {:.2g}", *d.value, *d.standard_error);
  return fmt::format("{:.6g}", *d.value);
}

}  // namespace

CDriveReport CalcCDriveReport(const CDriveSection& cdrive, const CDriveControlSection* control,
                              const std::vector<ParameterEstimate>& estimates, const std::string& source) {
  CDriveReport report;
  report.source = source;
  report.lead = cdrive.lead.value_or(0.0);
  report.jacobian = CalcCDriveJacobian(report.lead);
  report.jacobian_inverse = CalcCDriveJacobianInverse(report.lead);
  report.jtj = report.lead * report.lead / (8 * M_PI * M_PI);
  if (cdrive.hub_inertia && cdrive.collar_inertia && cdrive.collar_mass) {
    const CDriveParameters p = ModelValuesOrNaN(CDriveParameterTable(), cdrive);
    report.inertia = CDriveReport::Inertia{CalcInertiaDiagonal(p), CalcInertiaOffDiagonal(p), p.collar_inertia,
                                           std::pow(p.lead / (2 * M_PI), 2) * p.collar_mass};
  }
  for (const auto& paper : kTableOne) {
    const std::string key = KeyOf(CDriveParameterTable(), paper.member);
    const auto* row = FindParameter(CDriveParameterTable(), key);
    report.dissipation.push_back({key, cdrive.*(row->in_section), StandardError(estimates, key), paper.value});
  }
  if (control != nullptr) report.control = MakeControlSettings(*control);
  return report;
}

std::string FormatCDriveReport(const CDriveReport& report) {
  const Matrix2& j = report.jacobian;
  const Matrix2& inverse = report.jacobian_inverse;
  std::string out = fmt::format("C-drive from {} (seed 001; docs/models.md#c-drive), lead p = {} m\n\n", report.source,
                                report.lead);
  out += "kinematics w = (u, v) = J psi, v = p theta / (2 pi):\n";
  out += fmt::format("  J    = p/(4 pi) [[1, -1], [1, 1]]    = [[{:.6g}, {:.6g}], [{:.6g}, {:.6g}]] m/rad\n", j(0, 0),
                     j(0, 1), j(1, 0), j(1, 1));
  out += fmt::format("  J^-1 = (2 pi/p) [[1, 1], [-1, 1]]    = [[{:.6g}, {:.6g}], [{:.6g}, {:.6g}]] rad/m "
                     "(the seed prints pi/p, which gives J J^-1 = 1/2)\n",
                     inverse(0, 0), inverse(0, 1), inverse(1, 0), inverse(1, 1));
  out += fmt::format("  J'J  = p^2/(8 pi^2) 1 = {:.6g} 1 m^2/rad^2: isotropic, condition number 1\n", report.jtj);
  if (report.inertia) {
    const double a = report.inertia->a, b = report.inertia->b;
    out += "\ninertia (eq. 17): M = [[a, b], [b, a]]\n";
    out += fmt::format("  a = I_h + I_c/4 + p^2 m/(16 pi^2) = {:.6g} kg m^2\n", a);
    out += fmt::format("  b = I_c/4 - p^2 m/(16 pi^2)       = {:.6g} kg m^2\n", b);
    out += fmt::format("  eigenvalues a + b = {:.6g} (rotation), a - b = {:.6g} (translation); condition number {:.4g}\n",
                       a + b, a - b, std::max(a + b, a - b) / std::min(a + b, a - b));
    out += fmt::format("  isotropic (M proportional to 1, eq. 18) needs I_c = (p/2pi)^2 m = {:.4g} kg m^2; here I_c = "
                       "{:.4g}: {}\n",
                       report.inertia->isotropic_collar_inertia, report.inertia->collar_inertia,
                       std::abs(b) <= 1e-3 * a ? "isotropic" : "not isotropic, the motors are coupled");
  } else {
    out += "\ninertia: I_h, I_c, m not all given\n";
  }
  out += "\ndissipation (Table I):\n";
  out += fmt::format("  {:<18} {:<34} {:<34}\n", "part", "viscous [N m s/rad]", "Coulomb [N m]");
  // Table I's layout: viscous and Coulomb of the rotational parts, then of the collar.
  const auto& d = report.dissipation;
  out += fmt::format("  {:<18} {:<34} {:<34}\n", "rotational parts", d[0].key + " = " + Value(d[0]),
                     d[2].key + " = " + Value(d[2]));
  out += fmt::format("  {:<18} {:<34} {:<34}\n", "collar", d[1].key + " = " + Value(d[1]),
                     d[3].key + " = " + Value(d[3]));
  out += fmt::format("  paper Table I:     {} = {}, {} = {}, {} = {}, {} = {}\n", d[0].key, d[0].table_one, d[1].key,
                     d[1].table_one, d[2].key, d[2].table_one, d[3].key, d[3].table_one);
  std::string deviations;
  for (const auto& entry : d) {
    if (!entry.value) continue;
    deviations += fmt::format("{}{} {:+.2f} %", deviations.empty() ? "" : ", ", entry.key,
                              100.0 * (*entry.value / entry.table_one - 1.0));
  }
  if (!deviations.empty()) out += "  vs Table I:       " + deviations + "\n";
  if (report.control) {
    const CDriveControlSettings& c = *report.control;
    out += fmt::format("\ncontroller: {} at {} Hz, K_P = {} N m/rad, K_I = {} ({}), dead zone {} rad/s, rate limit {} /s\n",
                       ControlLawName(c.law), 1.0 / c.sample_time, c.proportional_gain, c.second_gain,
                       c.law == ControlLaw::kPD ? "read as a derivative gain, N m s/rad"
                                                : "integral gain, N m/(rad s)",
                       c.dead_zone, c.rate_limit);
  }
  return out;
}

Json CDriveReportJson(const CDriveReport& report) {
  const Matrix2& j = report.jacobian;
  const Matrix2& inverse = report.jacobian_inverse;
  Json out;
  out["source"] = report.source;
  out["lead"] = report.lead;
  out["jacobian"] = {j(0, 0), j(0, 1), j(1, 0), j(1, 1)};
  out["jacobian_inverse"] = {inverse(0, 0), inverse(0, 1), inverse(1, 0), inverse(1, 1)};
  out["jtj"] = report.jtj;
  if (report.inertia) {
    out["a"] = report.inertia->a;
    out["b"] = report.inertia->b;
  }
  out["dissipation"] = Json::object();
  for (const auto& d : report.dissipation) {
    out["dissipation"][d.key] = {{"value", d.value ? Json(*d.value) : Json(nullptr)},
                                 {"std", d.standard_error ? Json(*d.standard_error) : Json(nullptr)},
                                 {"table_one", d.table_one}};
  }
  return out;
}

}  // namespace driveid
