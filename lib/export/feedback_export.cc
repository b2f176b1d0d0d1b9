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
  Value(f, "kp");
  if (f.loop == "position") Value(f, "kd");
  Value(f, "period");
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
  if (!Pid(f)) return "";
  RequirePidValues(f);
  std::string out = fmt::format("\n  // Feedback: {} loop, preset {} (docs/models.md#feedback-gains).\n", CommentText(f.loop),
                                CommentText(f.preset));
  out += FeedbackVendorNote(f, "  //");
  for (const char* key : {"kp", "kd"}) {
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
  return RoboRioPid(f) ? "#include <frc/controller/PIDController.h>\n" : "";
}

std::string FeedbackCppMembers(const FeedbackController& f) {
  if (!Pid(f)) return "";
  RequirePidValues(f);
  std::string out = fmt::format("\n// Feedback: {} loop, preset {} (docs/models.md#feedback-gains).\n", CommentText(f.loop),
                                CommentText(f.preset));
  out += FeedbackVendorNote(f, "//");
  for (const char* key : {"kp", "kd"}) {
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
