#include "export/wpilib_export.h"

#include <array>
#include <cctype>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "core/errors.h"
#include "export/export_target.h"
#include "export/export_text.h"
#include "export/feedback_export.h"
#include "models/feedforward.h"

namespace driveid {
namespace {

using namespace export_text;

// Which WPILib class, and what it leaves out.
struct Plan {
  bool arm = false, elevator = false;
  const char* type = "SimpleMotorFeedforward";
  std::vector<std::string> notes;
};

Plan MakePlan(const WpilibAxis& axis) {
  const Feedforward& ff = axis.feedforward;
  Plan p;
  const FeedforwardGain* offset = Gain(ff, "offset");
  p.arm = Gain(ff, "Kg") && !axis.linear;
  // A linear axis's offset is an elevator's kG unless the logs were a SysId
  // "simple" test (a drive, a flywheel on a belt): there it is an offset.
  p.elevator = axis.linear && offset && offset->value != 0.0 && ff.mechanism != "simple";
  p.type = p.arm ? "ArmFeedforward" : p.elevator ? "ElevatorFeedforward" : "SimpleMotorFeedforward";
  if (p.arm) p.notes.push_back("ArmFeedforward measures the angle from horizontal: pass q - kGAngle.");
  if (!p.arm && !p.elevator && offset && offset->value != 0.0) {
    p.notes.push_back("The offset (kOffset) has no place in SimpleMotorFeedforward: add it to the output.");
  }
  p.notes.insert(p.notes.end(), axis.term_notes.begin(), axis.term_notes.end());
  return p;
}

// The gains in the order written, with their identifier.
std::vector<std::pair<std::string, std::string>> GainNames(const Plan& p) {
  return {{"Ks", "kS"},          {"Ks_forward", "kSForward"},  {"Ks_backward", "kSBackward"}, {"Kv", "kV"},
          {"Kv_forward", "kVForward"}, {"Kv_backward", "kVBackward"}, {"Ka", "kA"},             {"Kg", "kG"},
          {"Kg_angle", "kGAngle"}, {"offset", p.elevator ? "kGElevator" : "kOffset"}};
}

// The factories: name, kS and kV identifiers (per direction where fitted).
std::vector<std::array<std::string, 3>> Factories(const Feedforward& ff, const std::string& one) {
  if (Gain(ff, "Ks_forward")) {
    return {{one + "Forward", "kSForward", Gain(ff, "Kv_forward") ? "kVForward" : "kV"},
            {one + "Backward", "kSBackward", Gain(ff, "Kv_backward") ? "kVBackward" : "kV"}};
  }
  std::vector<std::array<std::string, 3>> out = {{one, "kS", Gain(ff, "Kv_forward") ? "kVForward" : "kV"}};
  if (Gain(ff, "Kv_backward")) out.push_back({one + "Backward", "kS", "kVBackward"});
  return out;
}

std::string Arguments(const Plan& p, const std::string& ks, const std::string& kv) {
  return p.arm ? fmt::format("{}, kG, {}, kA", ks, kv)
               : p.elevator ? fmt::format("{}, kGElevator, {}, kA", ks, kv) : fmt::format("{}, {}, kA", ks, kv);
}

std::string Law(const Plan& p, const Feedforward& ff) {
  return fmt::format("{}: u = Ks sgn(v) + Kv v + Ka a{} in {} and {} (docs/models.md#feed-forward)", p.type,
                     p.arm ? " + Kg cos(angle)" : p.elevator ? " + Kg" : "", CommentText(ff.effort_unit),
                     CommentText(ff.position_unit));
}

// The units library's type of a position unit, or "".
std::string DistanceType(const std::string& unit) {
  static const std::vector<std::pair<std::vector<std::string>, std::string>> kTypes = {
      {{"rad", "Radians", "radians", "Radian"}, "units::radians"},
      {{"rot", "Rotations", "rotations", "Rotation", "rev", "turns"}, "units::turns"},
      {{"deg", "Degrees", "degrees", "Degree"}, "units::degrees"},
      {{"m", "Meters", "meters", "Meter"}, "units::meters"},
      {{"mm"}, "units::millimeters"},
      {{"ft", "Feet", "feet"}, "units::feet"},
      {{"in", "Inches", "inches"}, "units::inches"}};
  for (const auto& [names, type] : kTypes) {
    for (const std::string& name : names) {
      if (unit == name) return type;
    }
  }
  return "";
}

}  // namespace

std::string ExportWpilibJava(const WpilibAxis& axis, const ExportOptions& o) {
  const Feedforward& ff = axis.feedforward;
  const Plan p = MakePlan(axis);
  std::string upper_first = o.joint;
  upper_first[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(upper_first[0])));
  const std::string cls = upper_first + "FeedforwardGains";
  std::string out = Provenance(o, "//", "");
  out += "// " + Law(p, ff) + "\n";
  for (const std::string& note : p.notes) out += "// " + note + "\n";
  out += "import edu.wpi.first.math.controller." + std::string(p.type) + ";\n";
  if (axis.feedback) out += FeedbackJavaImport(*axis.feedback);
  out += "\n";
  out += "public final class " + cls + " {\n  private " + cls + "() {}\n\n";
  for (const auto& [key, java] : GainNames(p)) {
    const FeedforwardGain* g = Gain(ff, key);
    if (!g) continue;
    out += fmt::format("  /** {} +- {:.3g} {} */\n  public static final double {} = {};\n", key, g->standard_error,
                       CommentText(g->unit), java, Number(g->value));
  }
  for (const auto& [name, ks, kv] : Factories(ff, "create")) {
    out += fmt::format("\n  public static {} {}() {{\n    return new {}({});\n  }}\n", p.type, name, p.type,
                       Arguments(p, ks, kv));
  }
  if (axis.feedback) out += FeedbackJavaMembers(*axis.feedback);
  out += "}\n";
  return out;
}

std::string ExportWpilibCpp(const WpilibAxis& axis, const ExportOptions& o) {
  const Feedforward& ff = axis.feedforward;
  const char* const target = ExportTargetName(ExportTarget::kWpilibCpp);
  if (ff.effort_unit != "V" && ff.effort_unit != "Volts" && ff.effort_unit != "volts") {
    throw InputError(fmt::format("{}: WPILib's feed-forward classes take volts, and this fit's effort is in "
                                 "'{}' (export it to {})", target, CommentText(ff.effort_unit),
                                 ListExportTargets({ExportTarget::kCHeader, ExportTarget::kJson})));
  }
  const std::string distance = DistanceType(ff.position_unit);
  if (distance.empty()) {
    throw InputError(fmt::format("{}: position unit '{}' has no units-library type here (radians, rotations, "
                                 "degrees, meters, millimeters, feet, inches)", target, CommentText(ff.position_unit)));
  }
  const Plan p = MakePlan(axis);
  // The units library checks a class's distance at compile time.
  const bool angle = IsAngleUnit(ff.position_unit);
  if ((axis.linear || p.elevator) == angle) {
    throw InputError(fmt::format("{}: a {} axis with its position in '{}': {} takes a {}", target, axis.linear ? "linear" : "rotary",
                                 ff.position_unit, p.type, angle ? "length (check axis.linear)" : "angle (check axis.linear)"));
  }
  std::string out = Provenance(o, "//", "");
  out += "// " + Law(p, ff) + "\n";
  for (const std::string& note : p.notes) out += "// " + note + "\n";
  out += "// Gains typed in the log's units; WPILib's units library converts them where the class fixes its own.\n";
  out += fmt::format("#pragma once\n\n#include <frc/controller/{}.h>\n#include <units/angle.h>\n#include <units/length.h>\n"
                     "#include <units/time.h>\n#include <units/voltage.h>\n{}\n",
                     p.type, axis.feedback ? FeedbackCppInclude(*axis.feedback) : "");
  out += fmt::format("namespace {}_feedforward {{\n\n", o.joint);
  out += fmt::format("using Distance = {};  // {}\n", distance, CommentText(ff.position_unit));
  out += "using Velocity = units::compound_unit<Distance, units::inverse<units::seconds>>;\n";
  out += "using Acceleration = units::compound_unit<Velocity, units::inverse<units::seconds>>;\n";
  out += fmt::format("using Feedforward = frc::{}{};\n\n", p.type, p.arm || p.elevator ? "" : "<Distance>");
  for (const auto& [key, name] : GainNames(p)) {
    const FeedforwardGain* g = Gain(ff, key);
    if (!g) continue;
    const std::string type = key.rfind("Kv", 0) == 0 ? "units::unit_t<units::compound_unit<units::volts, units::inverse<Velocity>>>"
                             : key == "Ka"           ? "units::unit_t<units::compound_unit<units::volts, units::inverse<Acceleration>>>"
                             : key == "Kg_angle"     ? "units::radian_t"
                                                     : "units::volt_t";
    out += fmt::format("/// {} +- {:.3g} {}\ninline constexpr {} {}{{{}}};\n", key, g->standard_error,
                       CommentText(g->unit), type, name, Number(g->value));
  }
  for (const auto& [factory, ks, kv] : Factories(ff, "Create")) {
    out += fmt::format("\ninline Feedforward {}() {{ return Feedforward{{{}}}; }}\n", factory, Arguments(p, ks, kv));
  }
  if (axis.feedback) out += FeedbackCppMembers(*axis.feedback);
  out += fmt::format("\n}}  // namespace {}_feedforward\n", o.joint);
  return out;
}

}  // namespace driveid
