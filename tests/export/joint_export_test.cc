// The elastic joint's exports (export/joint_export.h): the C header holds
// every joint value to the last bit with the gear ratio; the MJCF couples
// the two hinges by a tendon of stiffness k and damping d with the motor's
// armature J_m and gear n; a file without what a simulator needs is refused
// naming every missing key; targets without a joint form are refused
// naming the ones that have it.
#include <cstdlib>
#include <string>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "export/joint_export.h"
#include "params/parameter_file.h"
#include "models/joint.h"

namespace driveid {
namespace {

const char* kJoint =
    "joint:\n  gear_ratio: 50\n  motor_inertia: 0.021\n  link_inertia: 0.05\n  stiffness: 20.5\n  damping: 0.05\n"
    "  motor_viscous: 0.1\n  motor_coulomb: 0.2\n  link_viscous: 0.05\n  link_coulomb: 0.1\n  offset: 0.05\n";

double Constant(const std::string& text, const std::string& name) {
  const std::size_t at = text.find(name + " = ");
  REQUIRE(at != std::string::npos);
  return std::strtod(text.c_str() + at + name.size() + 3, nullptr);
}

TEST_CASE("C header: every joint value of the table and the gear ratio, to the last bit") {
  const ParameterFile file = ParseParameterFile("joint.yaml", kJoint);
  ExportOptions options;
  options.joint = "elbow";
  const std::string text = ExportJoint(*file.Find<JointSection>(), file, ExportTarget::kCHeader, options);
  CHECK(Constant(text, "ELBOW_gear_ratio") == 50.0);
  const JointSection& s = *file.Find<JointSection>();
  int values = 0;
  for (const auto& row : JointParameterTable()) {
    if (row.in_model == nullptr) continue;
    INFO(row.spec.key);
    CHECK(Constant(text, std::string("ELBOW_") + row.spec.key) == (s.*(row.in_section)).value_or(0.0));
    ++values;
  }
  CHECK(values >= 10);
}

TEST_CASE("MJCF: the tendon's stiffness and damping are k and d, the motor's armature J_m and gear n") {
  const ParameterFile file = ParseParameterFile("joint.yaml", kJoint);
  ExportOptions options;
  options.joint = "elbow";
  const std::string xml = ExportJoint(*file.Find<JointSection>(), file, ExportTarget::kMjcf, options);
  const std::size_t tendon = xml.find("<fixed");
  REQUIRE(tendon != std::string::npos);
  const std::string tag = xml.substr(tendon, xml.find('>', tendon) - tendon);
  CHECK(tag.find("stiffness=\"20.5\"") != std::string::npos);
  CHECK(tag.find("damping=\"0.050000000000000003\"") != std::string::npos);
  // The motor's armature is J_m less its body's own (a negligible 1e-9).
  const std::size_t motor = xml.find("name=\"elbow_motor\"");
  REQUIRE(motor != std::string::npos);
  const std::size_t armature = xml.find("armature=\"", motor);
  REQUIRE(armature != std::string::npos);
  CHECK(std::strtod(xml.c_str() + armature + 10, nullptr) == Approx(0.021).epsilon(1e-6));
  CHECK(xml.find("gear=\"50\"") != std::string::npos);
}

TEST_CASE("refused: what a simulator needs, every missing key named; targets without a joint form") {
  JointSection partial;  // (the reader itself requires the gear ratio)
  partial.motor_inertia = 0.02;
  partial.damping = 0.05;
  CHECK_THROWS_WITH(ExportJoint(partial, ParameterFile{}, ExportTarget::kMjcf, {}),
                    Catch::StartsWith("joint.gear_ratio, joint.link_inertia, joint.stiffness: a simulator model"));
  const ParameterFile file = ParseParameterFile("joint.yaml", kJoint);
  for (ExportTarget target : {ExportTarget::kWpilibJava, ExportTarget::kWpilibCpp, ExportTarget::kJson}) {
    CHECK_THROWS_WITH(ExportJoint(*file.Find<JointSection>(), file, target, {}),
                      Catch::Contains("mjcf, urdf or c-header"));
  }
}

}  // namespace
}  // namespace driveid
