#include "export/feedback_export.h"

#include <cctype>

#include <fmt/format.h>

#include "control/feedback_gains.h"
#include "core/errors.h"
#include "export/export_text.h"

namespace driveid {
namespace {

using namespace export_text;

bool Pid(const FeedbackController& f) { return !f.empty() && (f.loop == "velocity" || f.loop == "position"); }

// A value the export writes: refused by name when the section lacks it (an
// export never invents a gain of 0 or a period of 0).
double Value(const FeedbackController& f, const char* key) {
  const FeedbackValue* v = f.Find(key);
  if (v == nullptr) {
    throw InputError(fmt::format("feedback.{}: missing from the {} loop's section; an export would have to invent it "
                                 "(rerun drivetrain-fit gains)",
                                 key, CommentText(f.loop)));
  }
  if (std::string(key) == "period" && !(v->value > 0.0)) {
    throw InputError(fmt::format("feedback.period = {}: a controller period is > 0 s", v->value));
  }
  return v->value;
}

// The keys a PID export writes, checked before any text is made.
void RequirePidValues(const FeedbackController& f) {
  Value(f, kGainKp);
  if (f.loop == "position") Value(f, kGainKd);
  Value(f, "period");
}

bool Speed(const FeedbackController& f) { return !f.empty() && f.loop == "speed"; }

// The speed loop's keys an export writes, and its C(z), checked first.
void RequireSpeedValues(const FeedbackController& f) {
  Value(f, kGainKp);
  Value(f, kGainKi);
  Value(f, "period");
  if (f.numerator_z.empty() || f.denominator_z.empty()) {
    throw InputError("feedback.numerator_z, denominator_z: missing from the speed loop's section; the notch runs only "
                     "as C(z) (rerun drivetrain-fit gains ‹loop› speed)");
  }
}

std::string List(const std::vector<double>& values) {
  std::string out;
  for (std::size_t i = 0; i < values.size(); ++i) out += (i ? ", " : "") + Number(values[i]);
  return out;
}

// The speed loop in Java or C++ (`cpp`): its gains, period and notch as
// constants and C(z) as arrays, with the difference equation to run; no
// PIDController holds the notch, so none is made.
std::string SpeedLoopMembers(const FeedbackController& f, bool cpp) {
  RequireSpeedValues(f);
  const char* c = cpp ? "//" : "  //";
  const std::string scalar = cpp ? "inline constexpr double" : "  public static final double";
  std::string out = fmt::format(
      "\n{} Feedback: speed loop, preset {} (docs/models.md#feedback-gains): a PI with a notch at the resonance on the\n"
      "{} motor-speed error e. No PIDController holds the notch: run C(z) every kControllerPeriodSeconds,\n"
      "{} u[k] = sum_i kCzNumerator[i] e[k-i] - sum_(i>0) kCzDenominator[i] u[k-i].\n",
      c, CommentText(f.preset), c, c);
  for (const char* key : {kGainKp, kGainKi}) {
    const FeedbackValue* v = f.Find(key);
    out += fmt::format(cpp ? "/// {} +- {:.3g} {}\n" : "  /** {} +- {:.3g} {} */\n", key, v->standard_error,
                       CommentText(FeedbackGainUnit(f, key)));
    out += fmt::format("{} {} = {};\n", scalar, key[1] == 'p' ? "kP" : "kI", Number(v->value));
  }
  out += fmt::format("{} kControllerPeriodSeconds = {};\n", scalar, Number(Value(f, "period")));
  for (const auto& [key, name] : {std::pair{"notch_hz", "kNotchHz"}, std::pair{"notch_width_hz", "kNotchWidthHz"}}) {
    if (const FeedbackValue* v = f.Find(key)) out += fmt::format("{} {} = {};\n", scalar, name, Number(v->value));
  }
  for (const auto& [name, values] : {std::pair{"kCzNumerator", &f.numerator_z}, std::pair{"kCzDenominator", &f.denominator_z}}) {
    out += cpp ? fmt::format("inline constexpr std::array<double, {}> {}{{{}}};\n", values->size(), name, List(*values))
               : fmt::format("  public static final double[] {} = {{{}}};\n", name, List(*values));
  }
  return out;
}

// A WPILib PIDController runs the gains on the roboRIO: only for gains in its
// convention. A vendor's gains (per its own units, its 1 ms period, a kD per
// period) go into the vendor's slot, never into a PIDController.
bool RoboRioPid(const FeedbackController& f) {
  const ControllerPreset* preset = FindControllerPreset(f.preset);
  return Pid(f) && (!preset || preset->native_position[0] == '\0');
}

}  // namespace

std::string FeedbackCHeaderLines(const FeedbackController& f, const std::string& upper) {
  if (f.empty()) return "";
  if (Pid(f)) RequirePidValues(f);
  std::string out = fmt::format("\n/* feedback ({} loop, preset {}; docs/models.md#feedback-gains) */\n",
                                CommentText(f.loop), CommentText(f.preset));
  for (const auto& v : f.values) {
    std::string key = v.key;
    for (char& c : key) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    const std::string unit = FeedbackGainUnit(f, v.key);
    out += fmt::format("DRIVEID_CONSTANT {}_FEEDBACK_{} = {};{}\n", upper, key, Number(v.value),
                       unit.empty() ? "" : "  /* " + CommentText(unit) + " */");
    if (v.standard_error > 0.0) out += fmt::format("DRIVEID_CONSTANT {}_FEEDBACK_{}_STD = {:.6g};\n", upper, key, v.standard_error);
  }
  for (const auto& [name, coefficients] : {std::pair{"NUM", &f.numerator}, std::pair{"DEN", &f.denominator}}) {
    for (std::size_t i = 0; i < coefficients->size(); ++i) {
      out += fmt::format("DRIVEID_CONSTANT {}_FEEDBACK_C_{}{} = {};  /* s^{} */\n", upper, name, i,
                         Number((*coefficients)[i]), coefficients->size() - 1 - i);
    }
  }
  for (const auto& [name, coefficients] : {std::pair{"NUM", &f.numerator_z}, std::pair{"DEN", &f.denominator_z}}) {
    for (std::size_t i = 0; i < coefficients->size(); ++i) {
      out += fmt::format("DRIVEID_CONSTANT {}_FEEDBACK_CZ_{}{} = {};  /* z^-{} */\n", upper, name, i,
                         Number((*coefficients)[i]), i);
    }
  }
  return out;
}

std::string FeedbackJavaImport(const FeedbackController& f) {
  return RoboRioPid(f) ? "import edu.wpi.first.math.controller.PIDController;\n" : "";
}

std::string FeedbackJavaMembers(const FeedbackController& f) {
  if (Speed(f)) return SpeedLoopMembers(f, false);
  if (!Pid(f)) return "";
  RequirePidValues(f);
  std::string out = fmt::format("\n  // Feedback: {} loop, preset {} (docs/models.md#feedback-gains).\n", CommentText(f.loop),
                                CommentText(f.preset));
  out += FeedbackVendorNote(f, "  //");
  for (const char* key : {kGainKp, kGainKd}) {
    const FeedbackValue* v = f.Find(key);
    out += fmt::format("  /** {} +- {:.3g} {} */\n  public static final double {} = {};\n", key,
                       v ? v->standard_error : 0.0, CommentText(FeedbackGainUnit(f, key)),
                       key[1] == 'p' ? "kP" : "kD", Number(v ? v->value : 0.0));
  }
  out += fmt::format("  public static final double kControllerPeriodSeconds = {};\n", Number(Value(f, "period")));
  if (!RoboRioPid(f)) return out;  // the vendor's slot values only
  out += "\n  public static PIDController pidController() {\n"
         "    return new PIDController(kP, 0.0, kD, kControllerPeriodSeconds);\n  }\n";
  return out;
}

std::string FeedbackCppInclude(const FeedbackController& f) {
  if (Speed(f)) return "#include <array>\n";
  return RoboRioPid(f) ? "#include <frc/controller/PIDController.h>\n" : "";
}

std::string FeedbackCppMembers(const FeedbackController& f) {
  if (Speed(f)) return SpeedLoopMembers(f, true);
  if (!Pid(f)) return "";
  RequirePidValues(f);
  std::string out = fmt::format("\n// Feedback: {} loop, preset {} (docs/models.md#feedback-gains).\n", CommentText(f.loop),
                                CommentText(f.preset));
  out += FeedbackVendorNote(f, "//");
  for (const char* key : {kGainKp, kGainKd}) {
    const FeedbackValue* v = f.Find(key);
    out += fmt::format("/// {} +- {:.3g} {}\ninline constexpr double {} = {};\n", key, v ? v->standard_error : 0.0,
                       CommentText(FeedbackGainUnit(f, key)), key[1] == 'p' ? "kP" : "kD", Number(v ? v->value : 0.0));
  }
  if (!RoboRioPid(f)) {  // the vendor's slot values only
    out += fmt::format("inline constexpr double kControllerPeriodSeconds = {};\n", Number(Value(f, "period")));
    return out;
  }
  out += fmt::format("inline constexpr units::second_t kControllerPeriod{{{}}};\n", Number(Value(f, "period")));
  out += "\ninline frc::PIDController MakePIDController() { return frc::PIDController{kP, 0.0, kD, kControllerPeriod}; }\n";
  return out;
}

Json FeedbackJson(const FeedbackController& f) {
  if (f.empty()) return nullptr;
  if (Pid(f)) RequirePidValues(f);
  if (Speed(f)) RequireSpeedValues(f);
  Json out = {{"loop", f.loop}, {"preset", f.preset}, {"effort_unit", f.effort_unit}, {"position_unit", f.position_unit}};
  Json values = Json::object();
  for (const auto& v : f.values) {
    const FeedbackKey* declared = FindFeedbackKey(v.key);
    Json entry = {{"value", v.value}};
    if (declared != nullptr && declared->gain) entry["std"] = v.standard_error;
    if (declared != nullptr && declared->gain && v.HasInterval()) entry["ci95"] = {v.ci95_low, v.ci95_high};
    const std::string unit = FeedbackGainUnit(f, v.key);
    if (!unit.empty()) entry["unit"] = unit;
    values[v.key] = entry;
  }
  out["values"] = values;
  if (!f.numerator.empty()) out["c_s"] = {{"numerator", f.numerator}, {"denominator", f.denominator}};
  if (!f.numerator_z.empty()) out["c_z"] = {{"numerator", f.numerator_z}, {"denominator", f.denominator_z}};
  return out;
}

std::string FeedbackVendorNote(const FeedbackController& f, const char* c) {
  if (f.preset == "ctre-phoenix6") {
    return fmt::format("{} CTRE Phoenix 6: new Slot0Configs().withKP(kP).withKD(kD) (volts per rotation, per rotation/s); "
                       "these run in the Talon at 1 ms, not in a PIDController\n", c);
  }
  if (f.preset == "ctre-phoenix5") {
    return fmt::format("{} CTRE Phoenix 5: talon.config_kP(0, kP); talon.config_kD(0, kD); (1023/12 per volt, sensor "
                       "units, rate per 100 ms, kD per 1 ms period); not for a PIDController\n", c);
  }
  if (f.preset == "rev-neo" || f.preset == "rev-external") {
    return fmt::format("{} REV Spark MAX: closedLoop.pid(kP, 0.0, kD) in the slot's config (duty cycle, rotations, "
                       "rate per minute, kD per 1 ms period); not for a PIDController\n", c);
  }
  return "";
}

}  // namespace driveid
