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
      .Require(NotNegative(notch_width_hz), "‹notch_width›", notch_width_hz, "width >= 0 Hz (0: from the data)");
}
namespace {

// chi^2 quantiles at 95 % for 1 .. 6 degrees of freedom.
constexpr double kChiSquare95[] = {3.841, 5.991, 7.815, 9.488, 11.070, 12.592};

// The dynamic terms a speed loop's region spans (their keys: models/joint.h's table).
constexpr double JointParameters::*kDynamic[] = {&JointParameters::motor_inertia, &JointParameters::link_inertia,
                                                 &JointParameters::stiffness,     &JointParameters::damping,
                                                 &JointParameters::motor_viscous, &JointParameters::link_viscous};

// The plants at the ends of the principal axes of the 95 % region of the
// fitted dynamic parameters (those the fit estimated), each kept physical.
std::vector<SpeedLoopPlant> Region(const ParameterFile& file, const SpeedLoopPlant& nominal) {
  std::vector<double JointParameters::*> members;
  std::vector<std::string> keys;
  std::vector<double> stds;
  for (const auto member : kDynamic) {
    const std::string key = KeyOf(JointParameterTable(), member);
    for (const auto& e : file.fit_estimates) {
      if (e.name == key && e.standard_error > 0.0) {
        members.push_back(member);
        keys.push_back(key);
        stds.push_back(e.standard_error);
      }
    }
  }
  const std::size_t p = members.size();
  if (p == 0) return {};
  Eigen::MatrixXd covariance(p, p);
  for (std::size_t i = 0; i < p; ++i) {
    for (std::size_t j = 0; j < p; ++j) {
      covariance(i, j) = file.FitCorrelation(keys[i], keys[j]) * stds[i] * stds[j];
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
        double& value = edge.joint.*(members[i]);
        value = std::max(value + sign * radius * length * eigen.eigenvectors()(i, k), 1e-3 * std::abs(value));
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
  SpeedLoopSettings settings;
  settings.period = o.period;
  settings.phase_margin_deg = o.phase_margin_deg;
  settings.notch_width_hz = o.notch_width_hz;
  if (const auto* frf = file.Find<FrequencyResponseSection>()) settings.resonance_std_hz = frf->resonance_hz_std.value_or(0.0);
  JointGainsDesign d;
  const std::vector<SpeedLoopPlant> region = Region(file, plant);
  SpeedLoopDesign design;
  try {
    design = DesignSpeedLoop(plant, region, settings);
  } catch (const std::invalid_argument& e) {
    throw OptionError(e.what());
  }
  if (!design.met) {
    throw IdentificationError(fmt::format(
        "no PI speed loop with a notch at {:.4g} Hz meets a phase margin of {} deg, 6 dB gain margin and 0.5 modulus "
        "margin with a delay of 1.5 x {} s{}: try a shorter ‹period›, a smaller ‹phase_margin›, or a fit with "
        "narrower intervals",
        JointResonance(plant.joint) / (2.0 * M_PI), o.phase_margin_deg, o.period,
        region.empty() ? "" : " (and over the 95 % region, the phase margin less 10 deg)"));
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
  c.values.push_back({"kp", pi.kp, 0.0});
  c.values.push_back({"ki", pi.kp * pi.integral_corner, 0.0});
  c.values.push_back({"period", o.period, 0.0});
  c.values.push_back({"delay", 1.5 * o.period, 0.0});
  c.values.push_back({"notch_hz", pi.notch_hz, 0.0});
  c.values.push_back({"notch_width_hz", pi.notch_width_hz, 0.0});
  AddMargins("", design.nominal, c);
  if (!region.empty()) AddMargins("worst_", design.worst, c);
  c.numerator = pi.Numerator();
  c.denominator = pi.Denominator();
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
  PlotPanel gain{fmt::format("open loop C P e^(-1.5 T s): crossover {:.3g} Hz, gain margin {:.3g} dB, modulus margin {:.3g}",
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
