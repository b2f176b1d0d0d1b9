#include "report/drivetrain_report.h"

#include <cmath>

#include <fmt/format.h>

#include "report/fit_summary.h"

namespace driveid {
namespace {

// The numbers seed 000 prints in eq. (17) and the text after it.
constexpr double kPaperGain = 81.0;
constexpr double kPaperLagS2 = 5.249e-5;
constexpr double kPaperLagS1 = 0.031;
constexpr double kPaperNaturalFrequency = 138.0;
constexpr double kPaperDampingRatio = 0.9;
constexpr double kPaperStepTorque = -0.8;
constexpr double kPaperViscousFriction = 0.016;  // N m s/rad
constexpr double kPaperCoulombFriction = 5.0;    // N m
constexpr double kPaperSteadyState = -59.0;      // "-0.8 N m x 80 less the 5 N m Coulomb friction"

}  // namespace

DriveTrainQuantities CalcDriveTrainQuantities(const DriveTrainParameters& p) {
  DriveTrainQuantities d{};
  d.tf = CalcReducedTransferFunction(p);
  d.series_stiffness = CalcSeriesStiffness(p);
  const double drive = p.gear_ratio * kPaperStepTorque;
  d.stuck_level = drive - std::copysign(std::min(p.coulomb_friction, std::abs(drive)), drive);
  const double zeta = d.tf.damping_ratio;
  d.overshoot = zeta < 1.0 ? std::exp(-M_PI * zeta / std::sqrt(1.0 - zeta * zeta)) : 0.0;
  d.stuck_link_frequency = p.gearbox_inertia > 0.0 ? CalcStuckLinkFrequency(p) : 0.0;
  return d;
}

DriveTrainReport CalcDriveTrainReport(const DriveTrainParameters& params, const std::string& source,
                                      const DriveTrainParameters* fitted, const std::string& fitted_source) {
  DriveTrainReport report{source, params, CalcDriveTrainQuantities(params), std::nullopt, std::nullopt, fitted_source};
  if (fitted != nullptr) {
    report.fitted = *fitted;
    report.fitted_quantities = CalcDriveTrainQuantities(*fitted);
  }
  return report;
}

std::string FormatDriveTrainReport(const DriveTrainReport& report) {
  const DriveTrainParameters& p = report.params;
  const std::string& source = report.source;
  const std::string& fitted_source = report.fitted_source;
  const DriveTrainParameters* fitted = report.fitted ? &*report.fitted : nullptr;
  const DriveTrainQuantities& d = report.recomputed;
  const double n2 = p.gear_ratio * p.gear_ratio;
  std::string out = fmt::format("drive train from {} (seed 000 section 4; docs/models.md#drive-train)\n", source);
  out += fmt::format("  n_g^2 Theta_motor = {:.4g} kg m^2, n_g^2 Theta_g = {:.4g} kg m^2, n_g^2 d_g = {:.4g} N m s/rad\n",
                     n2 * p.motor_inertia, n2 * p.gearbox_inertia, n2 * p.viscous_friction);
  out += fmt::format("  k_eq = k_Tl k_Tg / (k_Tl + k_Tg) = {:.6g} N m/rad\n\n", d.series_stiffness);
  if (fitted != nullptr) out += fmt::format("fitted: {}\n", fitted_source);
  out += "eq. (16), reduced model: tau_link / tau_motor = K / (a2 s^2 + a1 s + 1)\n";
  const DriveTrainQuantities& f = report.fitted_quantities ? *report.fitted_quantities : d;
  auto row = [&](const char* name, double paper, double recomputed, double fit, const char* note) {
    std::string line = fmt::format("  {:<22} {:>11.6g} {:>12.6g}", name, paper, recomputed);
    if (fitted != nullptr) line += fmt::format(" {:>12.6g}", fit);
    return line + "   " + note + "\n";
  };
  out += fmt::format("  {:<22} {:>11} {:>12}{}   {}\n", "", "paper", "recomputed", fitted ? "       fitted" : "", "note");
  out += row("d_g [N m s/rad]", kPaperViscousFriction, p.viscous_friction, fitted ? fitted->viscous_friction : 0.0,
             "section 4: best match of Fig. 6");
  out += row("tau_c [N m]", kPaperCoulombFriction, p.coulomb_friction, fitted ? fitted->coulomb_friction : 0.0,
             "section 4: the 'gain loss' of Fig. 6");
  out += row("gain K [-]", kPaperGain, d.tf.gain, f.tf.gain, "misprint (81): the steady-state gain is n_g");
  out += row("a2 [s^2]", kPaperLagS2, d.tf.lag_s2, f.tf.lag_s2, "n_g^2 Theta_motor / k_eq");
  out += row("a1 [s]", kPaperLagS1, d.tf.lag_s1, f.tf.lag_s1, "misprint: 0.013 s intended (only it gives zeta = 0.9)");
  out += row("omega_n [1/s]", kPaperNaturalFrequency, d.tf.natural_frequency, f.tf.natural_frequency, "1 / sqrt(a2)");
  out += row("zeta [-]", kPaperDampingRatio, d.tf.damping_ratio, f.tf.damping_ratio, "a1 omega_n / 2");
  out += row("steady state [N m]", kPaperSteadyState, d.stuck_level, f.stuck_level,
             "after the -0.8 N m step: n_g tau_motor + tau_c (stuck)");
  out += fmt::format("\npaper experiment (Fig. 6): tau_motor step {} N m: ideal n_g tau_motor = {:.4g} N m; Coulomb "
                     "friction tau_c = {:.4g} N m makes the drive stick near {:.4g} N m (sliding overshoot {:.2g} %)\n",
                     kPaperStepTorque, p.gear_ratio * kPaperStepTorque, p.coulomb_friction, d.stuck_level,
                     100.0 * d.overshoot);
  if (d.stuck_link_frequency > 0.0) {
    out += fmt::format("full model: link mode with the motor stuck sqrt((k_Tl + k_Tg) / (n_g^2 Theta_g)) = {:.4g} rad/s "
                       "({:.4g} Hz), undamped\n",
                       d.stuck_link_frequency, d.stuck_link_frequency / (2 * M_PI));
  }
  out += "seed misprints corrected (docs/models.md#drive-train): (13) viscous term n_g^2 d_g phi' (printed theta_g); (14) right side "
         "k_Tg phi (printed k_T,k); n_g^2 Theta_g = 0.043 (printed 0.413)\n";
  return out;
}

namespace {
Json QuantitiesJson(const DriveTrainQuantities& d) {
  return {{"gain", d.tf.gain},
          {"a2", d.tf.lag_s2},
          {"a1", d.tf.lag_s1},
          {"natural_frequency", d.tf.natural_frequency},
          {"damping_ratio", d.tf.damping_ratio},
          {"steady_state", d.stuck_level},
          {"overshoot", d.overshoot},
          {"series_stiffness", d.series_stiffness},
          {"stuck_link_frequency", d.stuck_link_frequency}};
}
}  // namespace

Json DriveTrainReportJson(const DriveTrainReport& report) {
  Json out;
  out["source"] = report.source;
  out["recomputed"] = QuantitiesJson(report.recomputed);
  if (report.fitted_quantities) out["fitted"] = QuantitiesJson(*report.fitted_quantities);
  const auto key = [](double DriveTrainParameters::*member) { return KeyOf(DriveTrainParameterTable(), member); };
  out["paper"] = {{key(&DriveTrainParameters::viscous_friction), kPaperViscousFriction},
                  {key(&DriveTrainParameters::coulomb_friction), kPaperCoulombFriction},
                  {"gain", kPaperGain},             {"a2", kPaperLagS2},
                  {"a1", kPaperLagS1},              {"natural_frequency", kPaperNaturalFrequency},
                  {"damping_ratio", kPaperDampingRatio}, {"steady_state", kPaperSteadyState}};
  return out;
}

}  // namespace driveid
