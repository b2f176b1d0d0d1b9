#include "workflow/feedback_design.h"

#include <cmath>
#include <stdexcept>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "control/feedback_gains.h"
#include "core/errors.h"
#include "core/option_check.h"
#include "export/export_text.h"

namespace driveid {

bool AxisGainsOptions::IsValid(std::string* error) const {
  return OptionCheck(error)
      .Require(loop == "velocity" || loop == "position",
               "‹loop›: velocity or position for an axis (speed: an elastic joint's section)")
      .Require(!period || Positive(*period), "‹period›", period.value_or(0.0), "period > 0 s")
      .Require(!delay || NotNegative(*delay), "‹delay›", delay.value_or(0.0), "delay >= 0 s")
      .Require(NotNegative(max_position_error), "‹max_position_error›", max_position_error, "> 0 (0: SysId's)")
      .Require(NotNegative(max_velocity_error), "‹max_velocity_error›", max_velocity_error, "> 0 (0: SysId's)")
      .Require(Positive(max_effort), "‹max_effort›", max_effort, "> 0")
      .Require(NotNegative(conversion), "‹conversion›", conversion, "> 0 (0: from the preset's unit)")
      .Require(!kv || Finite(*kv), "‹kv›", kv.value_or(0.0), "finite")
      .Require(!ka || Finite(*ka), "‹ka›", ka.value_or(0.0), "finite")
      .Require(NotNegative(kv_std), "‹kv_std›", kv_std, ">= 0")
      .Require(NotNegative(ka_std), "‹ka_std›", ka_std, ">= 0");
}
namespace {

// Kv and Ka from the file: the feed-forward section (with stds and the
// fit's correlation of viscous and inertia), else the axis section.
void TakeFromFile(const ParameterFile& file, const std::string& path, AxisGainsDesign& d) {
  const Feedforward& ff = file.feedforward;
  if (!ff.gains.empty() && ff.law == kAxisFeedforwardLaw) {
    const FeedforwardGain* kv = export_text::Gain(ff, "Kv");
    const FeedforwardGain* ka = export_text::Gain(ff, "Ka");
    if (!kv || !ka) {
      throw InputError(fmt::format("{}: the feed-forward section has no {}{}: give ‹kv› and ‹ka›", path,
                                   kv ? "" : "Kv", ka ? "" : kv ? "Ka" : " and Ka"));
    }
    d.kv = kv->value;
    d.kv_std = kv->standard_error;
    d.ka = ka->value;
    d.ka_std = ka->standard_error;
    // Kv = b and Ka = J (models/feedforward.h): their correlation is the fit's.
    d.correlation = file.FitCorrelation("viscous", "inertia");
    if (const FeedforwardGain* ks = export_text::Gain(ff, "Ks")) d.ks = ks->value;
    d.controller.effort_unit = ff.effort_unit;
    d.controller.position_unit = ff.position_unit;
    d.kv_source = fmt::format("{} feed-forward (Kv, Ka with std{})", path,
                              file.fit_correlations.empty() ? "; no fit correlation: taken as 0" : " and correlation");
    if (export_text::Gain(ff, "Kv_forward") || export_text::Gain(ff, "Kv_backward")) {
      d.notes.push_back("the axis has direction-dependent Kv: the gains use the common Kv");
    }
    return;
  }
  const AxisSection* axis = file.Find<AxisSection>();
  if (!axis) {
    throw InputError(fmt::format("{}: no 'feedforward' or 'axis' section to take Kv and Ka from (an axis fit writes "
                                 "both; or give ‹kv› and ‹ka›)", path));
  }
  d.kv = axis->viscous.value_or(0.0);
  d.ka = axis->inertia.value_or(0.0);
  d.controller.effort_unit = axis->linear ? "N" : "N m";
  d.controller.position_unit = axis->linear ? "m" : "rad";
  d.kv_source = fmt::format("{} axis section (Kv = viscous, Ka = inertia; no std: the section carries none)", path);
}

// The weights not given, as SysId sets them: on data in volts (a fit's Kv
// and Ks) as its GUI does on loading data, else its settings' defaults.
void SysIdWeights(const AxisGainsOptions& o, bool loop_position, AxisGainsDesign& d, double& qp, double& qv) {
  qp = o.max_position_error;
  qv = o.max_velocity_error;
  const bool volts = d.controller.effort_unit.empty() || d.controller.effort_unit == "V";
  const bool loaded = d.ks.has_value() && volts && !o.kv && d.kv > 0.0 && kSysIdBatteryVolts - *d.ks > 0.0;
  // A velocity loop has no position weight; it is set (to SysId's) only so
  // that the settings are complete.
  if (!(qp > 0.0) && !loop_position) qp = loaded ? kSysIdLoadedPositionError : kSysIdMaxPositionError;
  if (qv > 0.0 && qp > 0.0) return;
  std::vector<std::string> set;
  if (!(qv > 0.0)) {
    qv = loaded ? (kSysIdBatteryVolts - *d.ks) / (4.0 * d.kv) : kSysIdMaxVelocityError;
    set.push_back(loaded ? fmt::format("max velocity error (12 V - Ks) / (4 Kv) = {:.5g}", qv)
                         : fmt::format("max velocity error {:g}", qv));
  }
  if (!(qp > 0.0)) {
    qp = loaded ? kSysIdLoadedPositionError : kSysIdMaxPositionError;
    if (loop_position) set.push_back(fmt::format("max position error {:g}", qp));
  }
  d.notes.push_back(fmt::format(
      "LQR weights as SysId{}: {}, max effort {:g} (‹max-velocity-error›, ‹max-position-error›, ‹max-effort› set "
      "them)",
      loaded ? "'s GUI sets them on loading data (allwpilib sysid/src/main/native/cpp/view/Analyzer.cpp, "
               "ConfigParamsOnFileSelect)"
             : " uses them with no data loaded (its settings' defaults: no fit in volts with Ks here)",
      fmt::join(set, ", "), o.max_effort));
}

LqrSettings Settings(const AxisGainsOptions& o, const ControllerPreset& preset, double qp, double qv) {
  LqrSettings s;
  s.period = o.period.value_or(preset.period);
  s.delay = o.delay.value_or(preset.delay);
  s.max_position_error = qp;
  s.max_velocity_error = qv;
  s.max_effort = o.max_effort;
  if (!(s.period > 0.0) || !(s.delay >= 0.0) || !(s.max_position_error > 0.0) || !(s.max_velocity_error > 0.0) ||
      !(s.max_effort > 0.0) || !(o.conversion >= 0.0)) {
    throw OptionError("‹period›, ‹max_position_error›, ‹max_velocity_error›, ‹max_effort› and ‹conversion› must be "
                      "positive, ‹delay› not negative");
  }
  if (s.delay > 1000.0 * s.period) {
    throw OptionError(fmt::format("‹delay› {} s is more than 1000 periods of {} s", s.delay, s.period));
  }
  return s;
}

// The controller's position unit and units per file unit: the preset's own
// (Phoenix 6 and REV in rotations, converted from an angle unit; Phoenix 5
// in sensor units, which only ‹conversion› gives), else the log's.
void ControllerUnits(const AxisGainsOptions& o, const ControllerPreset& preset, const std::string& file_unit,
                     double& conversion, std::string& unit) {
  const std::string native = preset.native_position;
  const std::string shown = UnitTextProblem(file_unit).empty() ? file_unit : "?";
  if (native.empty()) {
    conversion = o.conversion > 0.0 ? o.conversion : 1.0;
    unit = conversion == 1.0 ? file_unit : fmt::format("controller unit ({:g} per {})", conversion, file_unit);
    return;
  }
  unit = native;
  if (o.conversion > 0.0) {
    conversion = o.conversion;
    return;
  }
  if (native == "rotation" && RotationsPerUnit(file_unit) > 0.0) {
    conversion = RotationsPerUnit(file_unit);
    return;
  }
  throw OptionError(
      native == "rotation"
          ? fmt::format("‹preset› {} works in rotations, and the file's position unit is '{}': give ‹conversion› "
                        "(motor rotations per {}: for metres, the gear ratio / the wheel's circumference, e.g. 6.75 / (pi x "
                        "0.1016 m) = 21.15 for a 6.75:1 drive on 4 in wheels)",
                        preset.name, shown, shown)
          : fmt::format("‹preset› {} works in the sensor's units: give ‹conversion› (sensor units per {}, e.g. "
                        "2048 per rotation for a Talon FX's integrated sensor, 4096 for a CTRE Mag Encoder)",
                        preset.name, shown));
}

// A gain below this fraction of the one the same loop gets without its
// measurement delay is useless: the delay, not the plant, set it.
constexpr double kUsefulGainFraction = 1e-3;

}  // namespace

AxisGainsDesign DesignAxisGains(const ParameterFile* file, const std::string& path, const AxisGainsOptions& o) {
  RequireValid(o);
  const ControllerPreset* preset = FindControllerPreset(o.preset);
  if (!preset) {
    std::string names;
    for (const auto& p : ControllerPresets()) names += (names.empty() ? "" : ", ") + std::string(p.name);
    throw OptionError(fmt::format("‹preset› '{}': one of {}", UnitTextProblem(o.preset).empty() ? o.preset : "?", names));
  }
  AxisGainsDesign d;
  if (file) TakeFromFile(*file, path, d);
  if (o.kv) d.kv = *o.kv, d.kv_std = o.kv_std, d.kv_source = "given";
  if (o.ka) d.ka = *o.ka, d.ka_std = o.ka_std, d.kv_source = o.kv ? "given" : d.kv_source + "; Ka given";
  if (o.kv || o.ka) d.correlation = (o.kv && o.ka) ? 0.0 : d.correlation;
  if (!file && !(o.kv && o.ka)) throw OptionError("gains needs a parameter file or both ‹kv› and ‹ka›");
  if (!(d.kv >= 0.0) || !(d.ka > 0.0) || !std::isfinite(d.kv) || !std::isfinite(d.ka)) {
    throw IdentificationError(fmt::format("Kv = {} and Ka = {}: LQR gains need Kv >= 0 and Ka > 0 (refit the axis with "
                                          "motion that determines them)", d.kv, d.ka));
  }
  const bool volts = d.controller.effort_unit.empty() || d.controller.effort_unit == "V";
  if (!volts && preset->output_factor != 1.0) {
    throw OptionError(fmt::format("‹preset› {} converts volts to its output, but the effort is in {}",
                                  preset->name, d.controller.effort_unit));
  }
  GainRequest request;
  request.loop = o.loop == "velocity" ? FeedbackLoop::kVelocity : FeedbackLoop::kPosition;
  double qp = 0.0, qv = 0.0;
  SysIdWeights(o, request.loop == FeedbackLoop::kPosition, d, qp, qv);
  request.lqr = Settings(o, *preset, qp, qv);
  request.output_factor = preset->output_factor;
  request.velocity_time_factor = preset->velocity_time_factor;
  request.normalized = preset->normalized;
  FeedbackController& c = d.controller;
  if (c.effort_unit.empty()) c.effort_unit = "V";
  if (c.position_unit.empty()) c.position_unit = "unit";
  double conversion = 1.0;
  std::string controller_unit;
  ControllerUnits(o, *preset, c.position_unit, conversion, controller_unit);
  if (conversion != 1.0 || controller_unit != c.position_unit) {
    d.notes.push_back(fmt::format("gains per {} (the {} preset's unit): {:.6g} {} per {} of the file", controller_unit,
                                  preset->name, conversion, controller_unit, c.position_unit));
  }
  request.conversion = conversion;
  const GainUncertainty g = SampleGains(d.kv, d.kv_std, d.ka, d.ka_std, d.correlation, request);
  if (request.lqr.delay > 0.0) {
    GainRequest undelayed = request;
    undelayed.lqr.delay = 0.0;
    const FeedbackGains free = ControllerGains(d.kv, d.ka, undelayed);
    for (const auto& [key, value, reference] : {std::tuple{kGainKp, g.value.kp, free.kp}, std::tuple{kGainKd, g.value.kd, free.kd}}) {
      if (std::abs(reference) > 0.0 && std::abs(value) < kUsefulGainFraction * std::abs(reference)) {
        d.warnings.push_back(fmt::format(
            "{} = {:.3g} is {:.1g} of the {:.3g} the same loop gets without its {:.4g} s measurement delay ({:.3g} "
            "periods): the delay, not the plant, sets it, and feedback this weak does nothing; shorten the delay (a "
            "faster velocity filter) or the period, or control from the rate that lags less",
            key, value, std::abs(value / reference), reference, request.lqr.delay,
            request.lqr.delay / request.lqr.period));
      }
    }
  }

  c.loop = o.loop;
  c.preset = preset->name;
  c.position_unit = controller_unit;
  c.values.push_back({kGainKp, g.value.kp, g.standard_error.kp, g.ci95_low.kp, g.ci95_high.kp});
  if (request.loop == FeedbackLoop::kPosition) {
    c.values.push_back({kGainKd, g.value.kd, g.standard_error.kd, g.ci95_low.kd, g.ci95_high.kd});
  }
  c.values.push_back({"period", request.lqr.period, 0.0});
  c.values.push_back({"delay", request.lqr.delay, 0.0});
  if (request.loop == FeedbackLoop::kPosition) c.values.push_back({"max_position_error", qp, 0.0});
  c.values.push_back({"max_velocity_error", qv, 0.0});
  c.values.push_back({"max_effort", o.max_effort, 0.0});
  c.values.push_back({"conversion", conversion, 0.0});
  if (d.ka < 1e-7 && request.loop == FeedbackLoop::kVelocity) {
    d.notes.push_back("Ka below 1e-7: the velocity follows the effort at once; no velocity feedback is needed (kp 0)");
  }
  return d;
}

std::string FormatAxisGainsPlant(const AxisGainsDesign& d) {
  return fmt::format("plant: Kv {:.6g} +- {:.3g}, Ka {:.6g} +- {:.3g} (correlation {:.3f}) from {}\n", d.kv, d.kv_std,
                     d.ka, d.ka_std, d.correlation, d.kv_source);
}

Json AxisGainsPlantJson(const AxisGainsDesign& d) {
  return {{"source", d.kv_source}, {"kv", {{"value", d.kv}, {"std", d.kv_std}}},
          {"ka", {{"value", d.ka}, {"std", d.ka_std}}}, {"correlation", d.correlation}};
}

}  // namespace driveid
