// models/serial_drive_term.h: the serial arm's drive terms as registered
// objects. The registry holds kSerialDriveTerms terms with distinct keys and
// members, in the order of the regressor's names; each term's column, summed
// with its parameter, is the drive torque written out here by hand
// (J_a a + b v + tau_c sgn v + tau_0, + d |v| where asked); the bounds are the
// physics' (an inertia and dissipations >= 0, an offset and an asymmetry of
// either sign); the parameter file reads and writes each term's key, the
// asked term only where asked, and refuses a drive without an always term.
#include <cmath>
#include <random>
#include <set>
#include <string>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "models/serial_drive_term.h"
#include "models/serial_dynamics.h"
#include "models/serial_robot.h"
#include "params/parameter_file.h"
#include "params/serial_robot_section.h"

using namespace driveid;

namespace {

const SerialDriveTerm& Term(const std::string& key) {
  for (const SerialDriveTerm* t : SerialDriveTerms()) {
    if (key == t->key()) return *t;
  }
  FAIL("no drive term " << key);
  throw std::logic_error("unreachable");
}

}  // namespace

TEST_CASE("serial drive terms: registered once each, in the regressor's order") {
  const auto& terms = SerialDriveTerms();
  REQUIRE(terms.size() == kSerialDriveTerms);
  CHECK(kSerialColumnsPerJoint == kInertialParameters + kSerialDriveTerms);
  std::set<std::string> keys;
  for (std::size_t a = 0; a < terms.size(); ++a) {
    keys.insert(terms[a]->key());
    for (std::size_t b = 0; b < a; ++b) CHECK(terms[a]->member() != terms[b]->member());
  }
  CHECK(keys.size() == terms.size());
  SerialRobot robot;
  SerialJoint joint;
  joint.name = "elbow";
  joint.body = "forearm";
  robot.joints.push_back(joint);
  robot.bodies.push_back({});
  const auto names = SerialParameterNames(robot);
  REQUIRE(names.size() == kSerialColumnsPerJoint);
  for (std::size_t k = 0; k < terms.size(); ++k) {
    CHECK(names[SerialDriveColumn(k)] == std::string(terms[k]->key()) + "_elbow");
  }
}

TEST_CASE("serial drive terms: the columns are the drive torque, the bounds the physics'") {
  SerialDriveParameters p;
  p.armature = 0.31;
  p.viscous = 1.7;
  p.coulomb = 0.9;
  p.offset = -0.25;
  p.viscous_asymmetry = 0.4;
  SerialJoint plain, per_direction;
  per_direction.viscous_per_direction = true;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int trial = 0; trial < 50; ++trial) {
    const double a = u(rng), v = trial == 0 ? 0.0 : u(rng);
    const double sign = v > 0.0 ? 1.0 : v < 0.0 ? -1.0 : 0.0;
    const double common = 0.31 * a + 1.7 * v + 0.9 * sign - 0.25;
    // b+ = 1.7 + 0.4 forwards, b- = 1.7 - 0.4 backwards.
    const double directional = 0.31 * a + (v > 0.0 ? 2.1 : 1.3) * v + 0.9 * sign - 0.25;
    for (const SerialJoint* joint : {&plain, &per_direction}) {
      double sum = 0.0;
      for (const SerialDriveTerm* t : SerialDriveTerms()) {
        if (t->Asked(*joint)) sum += p.*(t->member()) * t->Column(a, v);
      }
      CHECK(sum == Approx(joint == &plain ? common : directional).margin(1e-12));
    }
  }
  CHECK(Term("armature").nonnegative());
  CHECK(Term("viscous").nonnegative());
  CHECK(Term("coulomb").nonnegative());
  CHECK_FALSE(Term("offset").nonnegative());
  CHECK_FALSE(Term("viscous_asymmetry").nonnegative());
  CHECK_FALSE(Term("viscous_asymmetry").always());
  SerialJoint asked;
  Term("viscous_asymmetry").Ask(asked);
  CHECK(asked.viscous_per_direction);
}

TEST_CASE("serial drive terms: the parameter file's drives by the terms' keys") {
  const std::string head =
      "serial_robot:\n  urdf: arm.urdf\n  half_window: 0.05\n  base:\n"
      "    - lead: m_link\n      combination: {m_link: 1}\n      value: 1\n  drives:\n";
  const ParameterFile file = ParseParameterFile(
      "p.yaml", head + "    - {joint: a, armature: 0.1, viscous: 2, coulomb: 0.5, offset: -0.1}\n"
                       "    - {joint: b, armature: 0.2, viscous: 3, coulomb: 0.6, offset: 0.2, viscous_asymmetry: -0.7}\n");
  const SerialRobotSection& s = *file.Find<SerialRobotSection>();
  REQUIRE(s.drives.size() == 2);
  CHECK(s.drives[0].asked.empty());
  CHECK(s.drives[1].drive.viscous == 3.0);
  CHECK(s.drives[1].drive.viscous_asymmetry == -0.7);
  REQUIRE(s.drives[1].asked.size() == 1);
  CHECK(s.drives[1].asked[0] == "viscous_asymmetry");
  const std::string written = FormatParameterFile(file);
  CHECK(written.find("{joint: a, armature: 0.1, viscous: 2, coulomb: 0.5, offset: -0.1}") != std::string::npos);
  CHECK(written.find("offset: 0.2, viscous_asymmetry: -0.7}") != std::string::npos);
  const ParameterFile back = ParseParameterFile("q.yaml", written);
  CHECK(back.Find<SerialRobotSection>()->drives[1].drive.viscous_asymmetry == -0.7);
  CHECK_THROWS_WITH(ParseParameterFile("p.yaml", head + "    - {joint: a, armature: 0.1, viscous: 2, offset: 0}\n"),
                    Catch::Contains("serial_robot.drives[0]: needs joint, armature, viscous, coulomb and offset"));
  CHECK_THROWS_WITH(
      ParseParameterFile("p.yaml", head + "    - {joint: a, armature: 0.1, viscous: 2, coulomb: 1, offset: 0, stiction: 1}\n"),
      Catch::Contains("serial_robot.drives[0].stiction: unknown key (known: joint, armature, viscous, coulomb, offset, "
                      "viscous_asymmetry)"));
}
