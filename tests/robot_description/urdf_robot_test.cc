// URDF robots (robot_description/urdf_robot.h): joints in tree order with their frames,
// axes and limits; links carried by fixed joints merged into the body that
// moves them, the base's left out; refusals name the file and the joint.
#include <cmath>
#include <string>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "robot_description/urdf_robot.h"
#include "models/serial_dynamics.h"

using namespace driveid;
using Catch::Matchers::Contains;

namespace {

const char* kArm = R"(<?xml version="1.0"?>
<robot name="arm">
  <link name="base"><inertial><mass value="5"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <link name="upper">
    <inertial><origin xyz="0.3 0 0" rpy="0 0 0"/><mass value="2"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.04"/></inertial>
  </link>
  <link name="lower">
    <inertial><origin xyz="0.25 0 0" rpy="0 0 0"/><mass value="1.3"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.02"/></inertial>
  </link>
  <link name="tool">
    <inertial><origin xyz="0 0 0" rpy="0 0 0"/><mass value="0.5"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
  </link>
  <link name="slide"><inertial><mass value="0.7"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial></link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="upper"/><origin xyz="0 0 0.2" rpy="0 0 0"/><axis xyz="0 0 2"/>
    <limit lower="-2" upper="2" effort="100" velocity="3"/>
  </joint>
  <joint name="elbow" type="continuous">
    <parent link="upper"/><child link="lower"/><origin xyz="0.7 0 0" rpy="0 0 0"/><axis xyz="0 0 1"/>
  </joint>
  <joint name="flange" type="fixed">
    <parent link="lower"/><child link="tool"/><origin xyz="0.5 0 0" rpy="0 0 0"/>
  </joint>
  <joint name="rail" type="prismatic">
    <parent link="upper"/><child link="slide"/><origin xyz="0.1 0 0" rpy="0 1.5707963267948966 0"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.3" effort="50" velocity="0.5"/>
  </joint>
</robot>
)";

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("URDF: joints in tree order with frames, axes and limits; fixed links merged, the base's left out") {
  const UrdfRobot u = ParseUrdfRobot("arm.urdf", kArm);
  const SerialRobot& r = u.robot;
  REQUIRE(r.size() == 3);
  CHECK(r.name == "arm");
  CHECK(r.joints[0].name == "shoulder");
  CHECK(r.joints[0].parent == -1);
  CHECK(r.joints[0].axis.isApprox(Eigen::Vector3d::UnitZ()));  // normalised
  CHECK(r.joints[0].upper == 2.0);
  CHECK(r.joints[0].effort_limit == 100.0);
  CHECK(r.joints[1].name == "elbow");
  CHECK(r.joints[1].parent == 0);
  CHECK(std::isinf(r.joints[1].upper));  // continuous
  CHECK(r.joints[2].name == "rail");
  CHECK(r.joints[2].type == SerialJointType::kPrismatic);
  CHECK(r.joints[2].parent == 0);
  // lower (1.3 kg at 0.25) and tool (0.5 kg at 0.5) in one body.
  CHECK(r.bodies[1][0] == Approx(1.8));
  CHECK(r.bodies[1][1] == Approx(1.3 * 0.25 + 0.5 * 0.5));
  CHECK(r.bodies[1][9] == Approx(0.02 + 1.3 * 0.25 * 0.25 + 0.001 + 0.5 * 0.25));
  REQUIRE(u.notes.size() == 2);
  CHECK_THAT(u.notes[0], Contains("base") && Contains("left out"));
  CHECK_THAT(u.notes[1], Contains("tool") && Contains("merged"));
}

TEST_CASE("URDF: the parsed two-link arm has the planar closed-form torques") {
  // Gravity along -z while the arm turns about z: no gravity torque; the
  // two-link closed form's inertia and Coriolis terms remain.
  const SerialRobot r = ParseUrdfRobot("arm.urdf", kArm).robot;
  Eigen::VectorXd q(3), qd(3), qdd(3);
  q << 0.3, 0.8, 0.1;
  qd << -0.5, 1.2, 0.0;
  qdd << 0.7, -0.4, 0.0;
  // Without the rail's slide the elbow joint sees lower + tool: m2 = 1.8, c2 = 0.3444.
  SerialRobot two = r;
  two.joints.pop_back();
  two.bodies.pop_back();
  const double m2 = 1.8, c2 = (1.3 * 0.25 + 0.5 * 0.5) / 1.8, l1 = 0.7;
  const double i2 = 0.02 + 0.001 + 1.3 * std::pow(0.25 - c2, 2) + 0.5 * std::pow(0.5 - c2, 2);
  const double m1 = 2.0, c1 = 0.3, i1 = 0.04;
  const double cos2 = std::cos(q(1)), sin2 = std::sin(q(1));
  const double m11 = i1 + i2 + m1 * c1 * c1 + m2 * (l1 * l1 + c2 * c2 + 2 * l1 * c2 * cos2);
  const double m12 = i2 + m2 * (c2 * c2 + l1 * c2 * cos2), m22 = i2 + m2 * c2 * c2, h = m2 * l1 * c2 * sin2;
  const Eigen::VectorXd tau = CalcSerialRigidTorque(two, two.bodies, q.head(2), qd.head(2), qdd.head(2));
  CHECK(tau(0) == Approx(m11 * qdd(0) + m12 * qdd(1) - h * (2 * qd(0) * qd(1) + qd(1) * qd(1))));
  CHECK(tau(1) == Approx(m12 * qdd(0) + m22 * qdd(1) + h * qd(0) * qd(0)));
}

TEST_CASE("URDF refusals name the file and what is wrong") {
  const auto refused = [](const std::string& text, const std::string& what) {
    INFO("expected a refusal naming: " << what);
    try {
      ParseUrdfRobot("bad.urdf", text);
      FAIL("accepted");
    } catch (const InputError& e) {
      CHECK_THAT(e.what(), Contains("bad.urdf") && Contains(what));
    }
  };
  refused("<robot name='x'><link name='a'/>", "not a URDF");
  refused("not xml at all", "not a URDF");
  refused(Replace(kArm, "type=\"continuous\"", "type=\"floating\""), "elbow");
  refused(Replace(kArm, "<axis xyz=\"0 0 1\"/>", "<axis xyz=\"0 0 1\"/><mimic joint=\"flange\"/>"), "flange");
  refused(Replace(kArm, "<axis xyz=\"0 0 1\"/>", "<axis xyz=\"0 0 1\"/><mimic joint=\"shoulder\" multiplier=\"0\"/>"),
          "multiplier");
  refused(Replace(kArm, "<axis xyz=\"0 0 1\"/>", "<axis xyz=\"0 0 1\"/><mimic joint=\"elbow\"/>"), "returns to itself");
  refused(Replace(kArm, "<axis xyz=\"0 0 1\"/>", "<axis xyz=\"0 0 1\"/><dynamics damping=\"-1\"/>"), "dynamics");
  refused(Replace(kArm, "<mass value=\"1.3\"/>", "<mass value=\"nan\"/>"), "lower");
  refused(Replace(kArm, "<mass value=\"1.3\"/>", "<mass value=\"-1.3\"/>"), "lower");
  refused(Replace(kArm, "<axis xyz=\"0 0 2\"/>", "<axis xyz=\"0 0 0\"/>"), "shoulder");
  std::string deep = "<robot name='x'>";
  for (int i = 0; i < 100000; ++i) deep += "<a>";
  refused(deep, "nested");
  refused("<robot name='x'><link name='a'/><link name='b'/><joint name='j' type='fixed'><parent link='a'/>"
          "<child link='b'/></joint></robot>",
          "no revolute");
}

TEST_CASE("URDF: a mimic joint follows its leader (through a mimic of a mimic); <dynamics> is the prior's friction") {
  // The elbow follows the shoulder at -2 q + 0.1; the rail the elbow at
  // 0.5 q - 0.2: q_rail = -q_shoulder + 0.05 - 0.2.
  std::string text = Replace(kArm, "<axis xyz=\"0 0 1\"/>",
                             "<axis xyz=\"0 0 1\"/><mimic joint=\"shoulder\" multiplier=\"-2\" offset=\"0.1\"/>"
                             "<dynamics damping=\"0.4\" friction=\"0.2\"/>");
  text = Replace(text, "<axis xyz=\"1 0 0\"/>", "<axis xyz=\"1 0 0\"/><mimic joint=\"elbow\" multiplier=\"0.5\" offset=\"-0.2\"/>");
  const UrdfRobot r = ParseUrdfRobot("mimic.urdf", text);
  REQUIRE(r.robot.size() == 3);
  CHECK(SerialCoordinateNames(r.robot) == std::vector<std::string>{"shoulder"});
  const SerialJoint& elbow = r.robot.joints[1];
  const SerialJoint& rail = r.robot.joints[2];
  CHECK(elbow.mimic == 0);
  CHECK(elbow.mimic_multiplier == -2.0);
  CHECK(elbow.mimic_offset == Approx(0.1));
  CHECK(rail.mimic == 0);
  CHECK(rail.mimic_multiplier == Approx(-1.0));
  CHECK(rail.mimic_offset == Approx(0.05 - 0.2));
  CHECK(r.drives[1].viscous == 0.4);
  CHECK(r.drives[1].coulomb == 0.2);
  CHECK(r.drives[0].viscous == 0.0);
  Eigen::VectorXd q, qd, qdd;
  ExpandSerialMotion(r.robot, Eigen::VectorXd::Constant(1, 0.3), Eigen::VectorXd::Constant(1, 2.0),
                     Eigen::VectorXd::Constant(1, -1.0), q, qd, qdd);
  CHECK(q(1) == Approx(-0.5));
  CHECK(q(2) == Approx(-0.3 - 0.15));
  CHECK(qd(2) == Approx(-2.0));
  CHECK(qdd(1) == Approx(2.0));
}
