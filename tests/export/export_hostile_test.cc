// Exports under hostile text and values (issue 36): unit strings that would
// close a comment or start a Java \u escape, an XML comment's trailing "-",
// units the parameter file reader refuses by file and line, inertias a
// simulator cannot hold, and targets a file cannot be exported to.
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "export/export_target.h"
#include "export/export_text.h"
#include "export/parameter_export.h"
#include "params/parameter_file.h"

using namespace driveid;

namespace {

const char* kAxis = "axis:\n  inertia: 0.05\n  viscous: 0.2\n  coulomb: 1\n  gravity_cos: 4\n  gravity_sin: -3\n"
                    "feedforward:\n  law: axis\n  effort_unit: \"V\"\n  position_unit: \"Radians\"\n"
                    "  Ks: {value: 1, std: 0.1}\n  Kv: {value: 0.2, std: 0.01}\n  Ka: {value: 0.05, std: 0.001}\n"
                    "  Kg: {value: 5, std: 0.1}\n  Kg_angle: {value: -0.6435, std: 0.01}\n";

// The text outside comments: XML <!-- -->, C/Java /* */ and // to the line's end.
// An XML comment holding "--" is not well-formed: returned as "BROKEN".
std::string Code(const std::string& text, bool xml) {
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    if (xml && text.compare(i, 4, "<!--") == 0) {
      const std::size_t end = text.find("-->", i + 4);
      if (end == std::string::npos || text.substr(i + 4, end - i - 4).find("--") != std::string::npos) return "BROKEN";
      i = end + 3;
    } else if (!xml && text.compare(i, 2, "/*") == 0) {
      const std::size_t end = text.find("*/", i + 2);
      if (end == std::string::npos) return "BROKEN";
      i = end + 2;
    } else if (!xml && text.compare(i, 2, "//") == 0) {
      i = text.find('\n', i);
      if (i == std::string::npos) break;
    } else {
      out += text[i++];
    }
  }
  return out;
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

}  // namespace

TEST_CASE("comment text: no backslash, no closing sequence, no trailing dash, printable ASCII") {
  using export_text::CommentText;
  CHECK(CommentText("\\u002a/static{System.exit(7);}/\\u002a") == "?u002a/static{System.exit(7);}/?u002a");
  CHECK(CommentText("a--b-") == "a- -b- ");
  CHECK(CommentText("x */ y") == "x * / y");
  CHECK(CommentText(std::string("n\0l\n\xff", 5)) == "n?l??");
}

TEST_CASE("every target under hostile units set in code: no backslash, comment-closing or XML-breaking text") {
  ParameterFile file = ParseParameterFile("arm.yaml", kAxis);
  ExportOptions options;
  options.joint = "arm";
  for (const char* unit : {"\\u002a/static{System.exit(7);}/\\u002a", "--><option gravity=\"0 0 98.1\"/><!--",
                           "*/ int x; /*", "a--b-", "rad\\user"}) {
    file.feedforward.effort_unit = unit;
    file.feedforward.position_unit = unit;
    for (ExportTarget target : {ExportTarget::kMjcf, ExportTarget::kUrdf, ExportTarget::kWpilibJava,
                                ExportTarget::kCHeader, ExportTarget::kJson}) {
      INFO(unit << " to target " << static_cast<int>(target));
      const std::string out = ExportParameters(file, target, options);
      if (target == ExportTarget::kJson) continue;  // a JSON string: escaped, parsed in tests/cli/export_cli_test.sh
      CHECK(out.find('\\') == std::string::npos);
      const bool xml = target == ExportTarget::kMjcf || target == ExportTarget::kUrdf;
      const std::string code = Code(out, xml);
      INFO(out);
      CHECK(code != "BROKEN");
      for (const char* injected : {"gravity=", "<include", "int x", "System.exit", "98.1"}) {
        CHECK(code.find(injected) == std::string::npos);
      }
    }
  }
}

TEST_CASE("the parameter file refuses a unit that is not a unit name, by file and line") {
  const std::string hostile = Replace(kAxis, "effort_unit: \"V\"", "effort_unit: \"--><option gravity='0 0 98.1'/><!--\"");
  CHECK_THROWS_WITH(ParseParameterFile("arm.yaml", hostile),
                    Catch::StartsWith("arm.yaml:9:") && Catch::Contains("feedforward.effort_unit: not a unit name: "));
  const std::string java = Replace(kAxis, "position_unit: \"Radians\"", "position_unit: \"rad\\\\user\"");
  CHECK_THROWS_WITH(ParseParameterFile("arm.yaml", java),
                    Catch::Contains("feedforward.position_unit: not a unit name: the character '\\'"));
  CHECK_NOTHROW(ParseParameterFile("ok.yaml", Replace(kAxis, "position_unit: \"Radians\"", "position_unit: \"V/(m/s)\"")));
}

TEST_CASE("inertias a simulator cannot hold are refused by name; a small motor's is exported") {
  const ParameterFile tiny = ParseParameterFile("t.yaml", "axis:\n  inertia: 1e-10\n  viscous: 0\n  coulomb: 0\n");
  CHECK_THROWS_WITH(ExportParameters(tiny, ExportTarget::kMjcf, ExportOptions{}),
                    Catch::StartsWith("axis.inertia = 1e-10: below 1e-09"));
  const ParameterFile motor = ParseParameterFile("m.yaml", "axis:\n  inertia: 1e-7\n  viscous: 0\n  coulomb: 0\n");
  const std::string mjcf = ExportParameters(motor, ExportTarget::kMjcf, ExportOptions{});
  CHECK(mjcf.find("mass=\"9.9999999999999998e-13\"") != std::string::npos);
}

TEST_CASE("an elastic joint has no feed-forward: wpilib-cpp refused like wpilib-java and json") {
  const ParameterFile joint = ParseParameterFile(
      "j.yaml", "joint:\n  gear_ratio: 50\n  motor_inertia: 0.02\n  link_inertia: 0.05\n  stiffness: 20\n");
  for (ExportTarget target : {ExportTarget::kWpilibCpp, ExportTarget::kWpilibJava, ExportTarget::kJson}) {
    CHECK_THROWS_WITH(ExportParameters(joint, target, ExportOptions{}),
                      Catch::StartsWith("the elastic joint has no feed-forward section"));
  }
  CHECK_NOTHROW(ExportParameters(joint, ExportTarget::kCHeader, ExportOptions{}));
}

TEST_CASE("wpilib-cpp: a linear axis in radians and a rotary axis in meters are refused before the compiler does") {
  ParameterFile lift = ParseParameterFile("l.yaml", Replace(kAxis, "  gravity_sin: -3\n", "  gravity_sin: -3\n  linear: true\n"));
  lift.feedforward.gains.push_back({"offset", 2.0, 0.1, "V"});
  CHECK_THROWS_WITH(ExportParameters(lift, ExportTarget::kWpilibCpp, ExportOptions{}),
                    Catch::Contains("a linear axis with its position in 'Radians'"));
  ParameterFile arm = ParseParameterFile("a.yaml", kAxis);
  arm.feedforward.position_unit = "Meters";
  CHECK_THROWS_WITH(ExportParameters(arm, ExportTarget::kWpilibCpp, ExportOptions{}),
                    Catch::Contains("a rotary axis with its position in 'Meters'"));
  arm.feedforward.position_unit = "Radians";
  CHECK_NOTHROW(ExportParameters(arm, ExportTarget::kWpilibCpp, ExportOptions{}));
}

TEST_CASE("export targets: one table spells each name; parsing inverts it, and refuses with every name listed") {
  const ExportTarget all[] = {ExportTarget::kMjcf,      ExportTarget::kUrdf,    ExportTarget::kWpilibJava,
                              ExportTarget::kWpilibCpp, ExportTarget::kCHeader, ExportTarget::kJson};
  const std::vector<std::string> names = ExportTargetNames();
  REQUIRE(names.size() == 6);
  for (std::size_t i = 0; i < names.size(); ++i) {
    CHECK(ExportTargetName(all[i]) == names[i]);
    CHECK(ParseExportTarget(names[i]) == all[i]);
    for (std::size_t j = 0; j < i; ++j) CHECK(names[j] != names[i]);
  }
  CHECK(ListExportTargets() == "mjcf, urdf, wpilib-java, wpilib-cpp, c-header or json");
  CHECK(ListExportTargets({ExportTarget::kCHeader, ExportTarget::kJson}) == "c-header or json");
  CHECK(ListExportTargets({ExportTarget::kUrdf}) == "urdf");
  CHECK_THROWS_WITH(ParseExportTarget("MJCF"),
                    Catch::Contains("'MJCF': one of mjcf, urdf, wpilib-java, wpilib-cpp, c-header, json"));
  CHECK_THROWS_AS(ParseExportTarget(""), InputError);
}
