// The feedback section in the export targets (export/feedback_export.h):
// every value read back from the C header to the last bit, its std only
// when it has one, the speed loop's C(s) coefficients by power of s, the
// PID members only for a PID loop, and hostile names kept inside comments.
#include <cstdlib>
#include <regex>
#include <string>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "export/feedback_export.h"

namespace driveid {
namespace {

double Constant(const std::string& text, const std::string& name) {
  const std::size_t at = text.find(name + " = ");
  REQUIRE(at != std::string::npos);
  return std::strtod(text.c_str() + at + name.size() + 3, nullptr);
}

TEST_CASE("C header: each value to the last bit, stds only where there are, C(s) by power of s") {
  FeedbackController f;
  f.loop = "speed";
  f.preset = "custom";
  f.effort_unit = "N m";
  f.position_unit = "rad";
  f.values = {{"kp", 0.1 + 0.2, 1.0 / 3.0}, {"ki", 7.123456789012345e-5, 0.0}, {"period", 0.001, 0.0}};
  f.numerator = {0.3, 1.0 / 7.0};
  f.denominator = {1.0, 0.0};
  const std::string text = FeedbackCHeaderLines(f, "ELBOW");
  CHECK(Constant(text, "ELBOW_FEEDBACK_KP") == 0.1 + 0.2);
  CHECK(Constant(text, "ELBOW_FEEDBACK_KI") == 7.123456789012345e-5);
  CHECK(Constant(text, "ELBOW_FEEDBACK_PERIOD") == 0.001);
  CHECK(Constant(text, "ELBOW_FEEDBACK_KP_STD") == Approx(1.0 / 3.0).epsilon(1e-5));
  CHECK(text.find("ELBOW_FEEDBACK_KI_STD") == std::string::npos);
  CHECK(Constant(text, "ELBOW_FEEDBACK_C_NUM1") == 1.0 / 7.0);
  CHECK(Constant(text, "ELBOW_FEEDBACK_C_NUM0") == 0.3);
  CHECK(std::regex_search(text, std::regex(R"(ELBOW_FEEDBACK_C_NUM0 = [0-9.e+-]+;  /\* s\^1 \*/)")));
  CHECK(text.find("ELBOW_FEEDBACK_C_DEN1 = 0") != std::string::npos);
  CHECK(text.find("/* s^0 */") != std::string::npos);
  // A speed loop has no PIDController to hold its notch: none is made, and
  // without its C(z) the Java/C++ members are refused by name, not dropped.
  CHECK_THROWS_WITH(FeedbackJavaMembers(f), Catch::Contains("feedback.numerator_z, denominator_z"));
  CHECK_THROWS_WITH(FeedbackCppMembers(f), Catch::Contains("feedback.numerator_z, denominator_z"));
  CHECK(FeedbackJavaImport(f).empty());
  f.numerator_z = {0.25, -0.125};
  f.denominator_z = {1.0, -1.0};
  const std::string java = FeedbackJavaMembers(f), cpp = FeedbackCppMembers(f);
  CHECK(java.find("public static final double[] kCzNumerator = {0.25, -0.125};") != std::string::npos);
  CHECK(java.find("public static final double kI = 7.1234567890123452e-05;") != std::string::npos);
  CHECK(cpp.find("inline constexpr std::array<double, 2> kCzDenominator{1, -1};") != std::string::npos);
  CHECK(java.find("PIDController") == java.find("No PIDController") + 3);
  CHECK(FeedbackCppInclude(f) == "#include <array>\n");
  const Json json = FeedbackJson(f);
  CHECK(json["c_z"]["numerator"][1] == -0.125);
  CHECK(json["values"]["kp"]["std"] == 1.0 / 3.0);
  CHECK(json["values"]["kp"]["unit"] == "N m s/rad");
  CHECK(FeedbackCHeaderLines(FeedbackController{}, "X").empty());
}

TEST_CASE("a vendor's gains: its slot values only, no PIDController built from them") {
  FeedbackController f;
  f.loop = "position";
  f.preset = "ctre-phoenix6";
  f.effort_unit = "V";
  f.position_unit = "rotation";
  f.values = {{"kp", 12.5, 0.25}, {"kd", 0.75, 0.0}, {"period", 0.001, 0.0}};
  const std::string java = FeedbackJavaMembers(f), cpp = FeedbackCppMembers(f);
  CHECK(java.find("public static final double kP = 12.5;") != std::string::npos);
  CHECK(java.find("Slot0Configs") != std::string::npos);
  CHECK(java.find("new PIDController") == std::string::npos);
  CHECK(cpp.find("inline constexpr double kP = 12.5;") != std::string::npos);
  CHECK(cpp.find("frc::PIDController") == std::string::npos);
  CHECK(FeedbackJavaImport(f).empty());
  CHECK(FeedbackCppInclude(f).empty());
  for (const char* vendor : {"ctre-phoenix5", "rev-neo", "rev-external"}) {
    f.preset = vendor;
    CHECK(FeedbackJavaMembers(f).find("new PIDController") == std::string::npos);
    CHECK(FeedbackCppMembers(f).find("MakePIDController") == std::string::npos);
  }
}

TEST_CASE("a PID loop: kP, kD and the period in Java and C++; hostile names commented out") {
  FeedbackController f;
  f.loop = "position";
  f.preset = "wpilib";
  f.effort_unit = "V";
  f.position_unit = "Rotations";
  f.values = {{"kp", 12.5, 0.25}, {"kd", 0.75, 0.0}, {"period", 0.02, 0.0}};
  const std::string java = FeedbackJavaMembers(f), cpp = FeedbackCppMembers(f);
  CHECK(java.find("public static final double kP = 12.5;") != std::string::npos);
  CHECK(java.find("public static final double kD = 0.75;") != std::string::npos);
  CHECK(java.find("kControllerPeriodSeconds = 0.02;") != std::string::npos);
  CHECK(java.find("new PIDController(kP, 0.0, kD, kControllerPeriodSeconds)") != std::string::npos);
  CHECK(cpp.find("inline constexpr double kP = 12.5;") != std::string::npos);
  CHECK(cpp.find("kControllerPeriod{0.02}") != std::string::npos);
  CHECK(FeedbackJavaImport(f) == "import edu.wpi.first.math.controller.PIDController;\n");
  CHECK(FeedbackCppInclude(f) == "#include <frc/controller/PIDController.h>\n");
  // A preset name that would close a comment and start code stays inside it.
  f.preset = "x */ int evil; /*";
  const std::string header = FeedbackCHeaderLines(f, "AXIS");
  const std::string first_line = header.substr(1, header.find('\n', 1) - 1);
  INFO(first_line);
  CHECK(std::regex_match(first_line, std::regex(R"(/\* [^*]*(\*[^/][^*]*)* \*/)")));
  CHECK(FeedbackJavaMembers(f).find("\n  // Feedback: position loop, preset x ") != std::string::npos);
}

}  // namespace
}  // namespace driveid

namespace driveid {
namespace {

TEST_CASE("a PID export refuses a section without kp, kd or a period instead of writing 0") {
  FeedbackController f;
  f.loop = "position";
  f.preset = "wpilib";
  f.effort_unit = "V";
  f.position_unit = "Rotations";
  f.values = {{"kp", 12.5, 0.25}, {"period", 0.02, 0.0}};  // no kd
  CHECK_THROWS_WITH(FeedbackJavaMembers(f), Catch::Contains("feedback.kd: missing"));
  CHECK_THROWS_WITH(FeedbackCppMembers(f), Catch::Contains("feedback.kd: missing"));
  CHECK_THROWS_WITH(FeedbackCHeaderLines(f, "AXIS"), Catch::Contains("feedback.kd: missing"));
  f.values = {{"kp", 12.5, 0.25}, {"kd", 0.5, 0.0}, {"period", -0.02, 0.0}};
  CHECK_THROWS_WITH(FeedbackJavaMembers(f), Catch::Contains("feedback.period = -0.02"));
  f.values = {{"kd", 0.5, 0.0}, {"period", 0.02, 0.0}};
  CHECK_THROWS_AS(FeedbackCppMembers(f), InputError);
}

}  // namespace
}  // namespace driveid
