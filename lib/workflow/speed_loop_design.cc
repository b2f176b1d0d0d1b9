// `gains --loop speed` (workflow/feedback_design.h): the joint section and the
// 95 % region of its fitted parameters, handed to control/speed_loop.h.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "control/speed_loop.h"
#include "core/errors.h"
#include "core/option_check.h"
#include "workflow/feedback_design.h"

namespace driveid {

bool JointGainsOptions::IsValid(std::string* error) const {
  return OptionCheck(error)
      .Require(Positive(period), "‹period›", period, "period > 0 s")
      .Require(phase_margin_deg > 0.0 && phase_margin_deg < 90.0, "‹phase_margin›", phase_margin_deg,
               "0 < margin < 90 degrees")
      .Require(NotNegative(notch_width_hz), "‹notch_width›", notch_width_hz, "width >= 0 Hz (0: from the data)")
      .Require(!delay || (NotNegative(*delay) && *delay <= 1000.0 * period), "‹delay›", delay.value_or(0.0),
               "0 <= delay <= 1000 periods");
}
namespace {

// chi^2 quantiles at 95 % for 1 .. 7 degrees of freedom.
constexpr double kChiSquare95[] = {3.841, 5.991, 7.815, 9.488, 11.070, 12.592, 14.067};

// The terms a speed loop's region spans: the joint's dynamic terms (their
// keys: models/joint.h's table) and the drive's delay (frf's key "delay").
struct RegionTerm {
  std::string key;
  double& (*value)(SpeedLoopPlant&);
};
const std::vector<RegionTerm>& RegionTerms() {
  static const std::vector<RegionTerm> terms = [] {
    std::vector<RegionTerm> t;
    const auto key = [](double JointParameters::*m) { return KeyOf(JointParameterTable(), m); };
    t.push_back({key(&JointParameters::motor_inertia), [](SpeedLoopPlant& p) -> double& { return p.joint.motor_inertia; }});
    t.push_back({key(&JointParameters::link_inertia), [](SpeedLoopPlant& p) -> double& { return p.joint.link_inertia; }});
    t.push_back({key(&JointParameters::stiffness), [](SpeedLoopPlant& p) -> double& { return p.joint.stiffness; }});
    t.push_back({key(&JointParameters::damping), [](SpeedLoopPlant& p) -> double& { return p.joint.damping; }});
    t.push_back({key(&JointParameters::motor_viscous), [](SpeedLoopPlant& p) -> double& { return p.joint.motor_viscous; }});
    t.push_back({key(&JointParameters::link_viscous), [](SpeedLoopPlant& p) -> double& { return p.joint.link_viscous; }});
    t.push_back({"delay", [](SpeedLoopPlant& p) -> double& { return p.delay; }});
    return t;
  }();
  return terms;
}

// The plants at the ends of the principal axes of the 95 % region of the
// fitted terms (those the fit estimated; the delay only when it is the
// fit's), each kept physical.
std::vector<SpeedLoopPlant> Region(const ParameterFile& file, const SpeedLoopPlant& nominal, bool fitted_delay) {
  std::vector<const RegionTerm*> members;
  std::vector<double> stds;
  for (const auto& term : RegionTerms()) {
    if (term.key == "delay" && !fitted_delay) continue;
    for (const auto& e : file.fit_estimates) {
      if (e.name == term.key && e.standard_error > 0.0) {
        members.push_back(&term);
        stds.push_back(e.standard_error);
      }
    }
  }
  const std::size_t p = members.size();
  if (p == 0) return {};
  Eigen::MatrixXd covariance(p, p);
  for (std::size_t i = 0; i < p; ++i) {
    for (std::size_t j = 0; j < p; ++j) {
      covariance(i, j) = file.FitCorrelation(members[i]->key, members[j]->key) * stds[i] * stds[j];
    }
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(covariance);
  const double radius = std::sqrt(kChiSquare95[p - 1]);
  std::vector<SpeedLoopPlant> out;
  for (std::size_t k = 0; k < p; ++k) {
    const double length = std::sqrt(std::max(0.0, eigen.eigenvalues()[k]));
    for (double sign : {-1.0, 1.0}) {
      SpeedLoopPlant edge = nominal;
      for (std::size_t i = 0; i < p; ++i) {
        double& value = members[i]->value(edge);
        const double floor = members[i]->key == "delay" ? 0.0 : 1e-3 * std::abs(value);
        value = std::max(value + sign * radius * length * eigen.eigenvectors()(i, k), floor);
      }
      out.push_back(edge);
    }
  }
  return out;
}

void AddMargins(const char* prefix, const LoopMargins& m, FeedbackController& c) {
  const std::string p = prefix;
  if (p.empty()) c.values.push_back({"crossover_hz", m.crossover_hz, 0.0});
  c.values.push_back({p + "phase_margin_deg", m.phase_margin_deg, 0.0});
  if (std::isfinite(m.gain_margin_db)) c.values.push_back({p + "gain_margin_db", m.gain_margin_db, 0.0});
  c.values.push_back({p + "modulus_margin", m.modulus_margin, 0.0});
}

}  // namespace

JointGainsDesign DesignJointGains(const ParameterFile& file, const std::string& path, const JointGainsOptions& o) {
  RequireValid(o);
  const JointSection* section = file.Find<JointSection>();
  if (!section) {
    throw InputError(fmt::format("{}: no 'joint' section for a speed loop (a two-mass fit of frf, or joint, writes it)", path));
  }
  SpeedLoopPlant plant;
  plant.joint = MakeModelParameters(JointParameterTable(), *section, JointParameters{}, "joint");
  plant.gear_ratio = section->gear_ratio.value_or(1.0);
  if (!(plant.joint.motor_inertia > 0.0) || !(plant.joint.link_inertia > 0.0) || !(plant.joint.stiffness > 0.0)) {
    throw InputError(fmt::format("{}: joint: a speed loop needs motor_inertia, link_inertia and stiffness > 0", path));
  }
  // The drive's delay: --delay, else the fit's (frf --free ...,delay), else none.
  const ParameterEstimate* fitted_delay = nullptr;
  for (const auto& e : file.fit_estimates) {
    if (e.name == "delay") fitted_delay = &e;
  }
  std::string delay_source;
  if (o.delay) {
    plant.delay = *o.delay;
    delay_source = "given (‹delay›)";
  } else if (fitted_delay) {
    if (!(fitted_delay->value >= -3.0 * fitted_delay->standard_error) || !std::isfinite(fitted_delay->value)) {
      throw InputError(fmt::format("{}: fit.estimates.delay = {:.4g} s: a negative delay is not a drive's; refit, or give "
                                   "‹delay›", path, fitted_delay->value));
    }
    plant.delay = std::max(0.0, fitted_delay->value);
    delay_source = fmt::format("fitted ({:.4g} +- {:.2g} ms)", 1e3 * fitted_delay->value, 1e3 * fitted_delay->standard_error);
  }
  if (plant.delay > 1000.0 * o.period) {
    throw OptionError(fmt::format("the drive's delay {} s is more than 1000 periods of {} s", plant.delay, o.period));
  }
  SpeedLoopSettings settings;
  settings.period = o.period;
  settings.phase_margin_deg = o.phase_margin_deg;
  settings.notch_width_hz = o.notch_width_hz;
  if (const auto* frf = file.Find<FrequencyResponseSection>()) settings.resonance_std_hz = frf->resonance_hz_std.value_or(0.0);
  JointGainsDesign d;
  const std::vector<SpeedLoopPlant> region = Region(file, plant, !o.delay && fitted_delay);
  const SpeedLoopDesign design = DesignSpeedLoop(plant, region, settings);
  const std::string delay_text =
      fmt::format("a loop delay of {:.4g} ms (the drive's {:.4g} ms{} + 1.5 x the period {} s)",
                  1e3 * plant.LoopDelay(o.period), 1e3 * plant.delay,
                  delay_source.empty() ? ", none measured" : ", " + delay_source, o.period);
  if (!design.met) {
    const LoopMargins& b = design.closest;
    throw IdentificationError(fmt::format(
        "no PI speed loop with a notch at {:.4g} Hz meets a phase margin of {} deg, 6 dB gain margin and 0.5 modulus "
        "margin with {}{}: {}; try a shorter ‹period›, a smaller ‹phase_margin›, or a fit with narrower intervals",
        JointResonance(plant.joint) / (2.0 * M_PI), o.phase_margin_deg, delay_text,
        region.empty() ? "" : " (and over the 95 % region, the phase margin less 10 deg)",
        design.nominal_only_crossover_hz > 0.0
            ? fmt::format("the largest crossover meeting them at the nominal plant is {:.4g} Hz, and the 95 % region "
                          "breaks it", design.nominal_only_crossover_hz)
            : b.stable ? fmt::format("the closest loop reaches a phase margin of {:.3g} deg, gain margin {:.3g} dB and "
                                     "modulus margin {:.3g} at {:.4g} Hz crossover",
                                     b.phase_margin_deg, b.gain_margin_db, b.modulus_margin, b.crossover_hz)
                       : "no crossover gives a stable loop"));
  }
  d.plant = plant;
  d.design = design;
  d.period = o.period;
  FeedbackController& c = d.controller;
  c.loop = "speed";
  c.preset = "custom";
  c.effort_unit = "N m";
  c.position_unit = "rad (motor)";
  const PiNotch& pi = design.controller;
  c.values.push_back({kGainKp, pi.kp, 0.0});
  c.values.push_back({kGainKi, pi.kp * pi.integral_corner, 0.0});
  c.values.push_back({"period", o.period, 0.0});
  c.values.push_back({"plant_delay", plant.delay, !o.delay && fitted_delay ? fitted_delay->standard_error : 0.0});
  c.values.push_back({"loop_delay", plant.LoopDelay(o.period), 0.0});
  c.values.push_back({"notch_hz", pi.notch_hz, 0.0});
  c.values.push_back({"notch_width_hz", pi.notch_width_hz, 0.0});
  AddMargins("", design.nominal, c);
  if (!region.empty()) AddMargins("worst_", design.worst, c);
  c.numerator = pi.Numerator();
  c.denominator = pi.Denominator();
  pi.Discrete(o.period, c.numerator_z, c.denominator_z);
  d.notes.push_back(fmt::format("designed for {}; C(z) by Tustin's rule prewarped at the notch", delay_text));
  if (delay_source.empty()) {
    d.notes.push_back("no measured delay of the drive: give ‹delay›, or fit it (frf's two-mass fit with delay among the free "
                      "parameters); "
                      "a drive's delay the loop does not know can destabilise it");
  }
  d.notes.push_back(region.empty()
                        ? "the file has no fit estimates with std: margins at the nominal plant only"
                        : fmt::format("worst margins over {} plants at the ends of the principal axes of the "
                                      "parameters' 95 % region", region.size()));
  return d;
}

std::vector<PlotPanel> SpeedLoopPanels(const JointGainsDesign& d) {
  const LoopMargins& m = d.design.nominal;
  std::vector<double> f, magnitude, phase, zero, minus180;
  const double nyquist = 0.5 / d.period;
  for (int i = 0; i < 600; ++i) f.push_back(0.01 * std::pow(nyquist / 0.01, i / 599.0));
  const auto l = OpenLoopResponse(d.plant, d.design.controller, d.period, f);
  double offset = 0.0;
  for (std::size_t i = 0; i < l.size(); ++i) {
    magnitude.push_back(20.0 * std::log10(std::abs(l[i])));
    double p = std::arg(l[i]) * 180.0 / M_PI + offset;
    if (i > 0) {
      while (p - phase.back() > 180.0) p -= 360.0, offset -= 360.0;
      while (p - phase.back() < -180.0) p += 360.0, offset += 360.0;
    }
    phase.push_back(p);
    zero.push_back(0.0);
    minus180.push_back(-180.0);
  }
  PlotPanel gain{fmt::format("open loop C P e^(-(tau_p + 1.5 T) s): crossover {:.3g} Hz, gain margin {:.3g} dB, modulus margin {:.3g}",
                             m.crossover_hz, m.gain_margin_db, m.modulus_margin),
                 "|L| [dB]", {{"|L(jw)|", f, magnitude}, {"0 dB", f, zero}}};
  PlotPanel angle{fmt::format("phase: margin {:.3g} deg; notch at {:.4g} Hz", m.phase_margin_deg,
                              d.design.controller.notch_hz),
                  "phase [deg]", {{"arg L(jw)", f, phase}, {"-180 deg", f, minus180}}};
  angle.own_x_label = "frequency [Hz]";
  angle.own_log_x = true;
  const double settle = std::max(20.0 / (2.0 * M_PI * std::max(m.crossover_hz, 1e-3)), 20.0 * d.period);
  const StepResponse step = SimulateSpeedStep(d.plant, d.design.controller, d.period, settle);
  PlotPanel response{"closed loop: unit step of the speed reference, identified model (torque one period late)",
                     "motor speed / reference", {{"motor speed", step.time, step.speed}}};
  response.own_x_label = "time [s]";
  return {gain, angle, response};
}

}  // namespace driveid
