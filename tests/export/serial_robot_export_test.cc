// A serial robot's exports (docs/export.md#serial-robot): the URDF keeps the
// user's file (comments, visuals, transmissions) and reads back with the
// identified bodies — the merged tool's inertial removed — and drives; the
// MJCF, in MuJoCo's inverse dynamics, gives the reference arm's torques
// from its independent Lagrangian (tests/support/reference_serial_arm.h).
#include <cmath>
#include <fstream>
#include <random>
#include <string>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "export/parameter_export.h"
#include "params/parameter_file.h"
#include "params/serial_robot_section.h"
#include "system/sha256.h"
#include "robot_description/urdf_robot.h"
#include "sim/mujoco_axis_simulator.h"
#include "sim/mujoco_inverse.h"
#include "support/private_tmpdir.h"
#include "support/reference_arm_urdf.h"
#include "support/reference_serial_arm.h"

using namespace driveid;

namespace {

struct Fixture {
  testing::PrivateTmpdir tmp;
  std::string urdf_path = tmp.path() + "/arm.urdf";
  std::string text;
  reference::Arm arm = reference::ThreeJointArm();
  ParameterFile file;
  SerialRobotSection section;

  // The "identified" bodies: the URDF's (the tool merged) scaled by `scale`.
  explicit Fixture(double scale) {
    text = reference::ArmUrdf(arm, true);
    std::ofstream(urdf_path) << text;
    section.urdf = urdf_path;
    section.urdf_sha256 = Sha256Hex(text);
    const SerialRobot robot = ParseUrdfRobot(urdf_path, text).robot;
    for (std::size_t j = 0; j < robot.size(); ++j) {
      InertialParameters p = robot.bodies[j];
      for (double& v : p) v *= scale;
      section.bodies.push_back({robot.joints[j].body, p});
      const reference::ArmJoint& a = arm.joints[j];
      section.drives.push_back({robot.joints[j].name, {a.armature, a.viscous, a.coulomb, a.offset}});
    }
    file.Set(section);
  }
  std::string Export(ExportTarget target) const {
    ExportOptions o;
    o.source = "arm.yaml";
    o.command = "drivetrain-fit export arm.yaml";
    return ExportParameters(file, target, o);
  }
};

double AttributeAfter(const std::string& text, const std::string& anchor, const std::string& attribute) {
  const std::size_t at = text.find(anchor);
  REQUIRE(at != std::string::npos);
  const std::size_t key = text.find(attribute + "=\"", at);
  REQUIRE(key != std::string::npos);
  return std::stod(text.substr(key + attribute.size() + 2));
}

}  // namespace

TEST_CASE("the URDF export keeps the user's file and reads back with the identified bodies and drives") {
  const Fixture f(1.1);
  const std::string urdf = f.Export(ExportTarget::kUrdf);
  CHECK(urdf.find("<!-- the reference arm -->") != std::string::npos);
  CHECK(urdf.find("package://arm/turret.stl") != std::string::npos);
  CHECK(urdf.find("SimpleTransmission") != std::string::npos);
  const SerialRobot back = ParseUrdfRobot("exported.urdf", urdf).robot;
  REQUIRE(back.size() == f.section.bodies.size());
  // The tool's own inertial is gone (it is in the last body): the bodies
  // read back are the section's exactly, not the section's plus the tool.
  for (std::size_t j = 0; j < back.size(); ++j) {
    for (std::size_t k = 0; k < kInertialParameters; ++k) {
      const double want = f.section.bodies[j].parameters[k];
      CHECK(back.bodies[j][k] == Approx(want).margin(1e-12 * (1.0 + std::abs(want))));
    }
    const SerialDriveParameters& d = f.section.drives[j].drive;
    const std::string anchor = "<joint name=\"" + back.joints[j].name + "\"";
    CHECK(AttributeAfter(urdf, anchor, "damping") == Approx(d.viscous).epsilon(1e-15));
    CHECK(AttributeAfter(urdf, anchor, "friction") == Approx(d.coulomb).epsilon(1e-15));
  }
  CHECK(back.joints.back().carried == std::vector<std::string>{"tool"});
}

TEST_CASE("a serial robot's export refuses another URDF, targets without a robot, and a file without bodies") {
  Fixture f(1.0);
  CHECK_THROWS_AS(f.Export(ExportTarget::kWpilibJava), InputError);
  SerialRobotSection other = f.section;
  other.urdf_sha256 = std::string(64, '0');
  f.file.Set(other);
  CHECK_THROWS_WITH(f.Export(ExportTarget::kUrdf), Catch::Contains("SHA-256 differs"));
  SerialRobotSection bare = f.section;
  bare.bodies.clear();
  f.file.Set(bare);
  CHECK_THROWS_WITH(f.Export(ExportTarget::kMjcf), Catch::Contains("no bodies"));
}

TEST_CASE("the MJCF export in MuJoCo's inverse dynamics gives the reference arm's torques") {
  std::string why;
  if (!MujocoAvailable(&why)) {
    WARN("skipped: " << why);
    return;
  }
  const Fixture f(1.0);
  const std::string xml = f.tmp.path() + "/arm.xml";
  std::ofstream(xml) << f.Export(ExportTarget::kMjcf);
  // The reference arm has no tool: its torques are the URDF's less the tool's, so compare
  // against the arm with the tool added to the last body by hand.
  reference::Arm arm = f.arm;
  reference::ArmJoint& last = arm.joints.back();
  const Eigen::Vector3d tool(reference::kToolOffsetX + reference::kToolCentreX, 0.0, 0.0);
  const double m = last.mass + reference::kToolMass;
  const Eigen::Vector3d c = (last.mass * last.centre + reference::kToolMass * tool) / m;
  const auto shift = [](double mass, const Eigen::Vector3d& d) {
    return Eigen::Matrix3d(mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose()));
  };
  last.inertia_at_centre = last.inertia_at_centre + shift(last.mass, last.centre - c) +
                           reference::kToolInertia * Eigen::Matrix3d::Identity() + shift(reference::kToolMass, tool - c);
  last.mass = m;
  last.centre = c;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-2.5, 2.5), rate(0.5, 2.0), accel(-5.0, 5.0);
  std::vector<Eigen::VectorXd> q, qd, qdd;
  for (int k = 0; k < 50; ++k) {
    Eigen::VectorXd a(3), v(3), w(3);
    for (int j = 0; j < 3; ++j) {
      a(j) = angle(rng);
      v(j) = (rng() % 2 ? 1.0 : -1.0) * rate(rng);  // moving: MuJoCo's friction loss at its full value
      w(j) = accel(rng);
    }
    q.push_back(a);
    qd.push_back(v);
    qdd.push_back(w);
  }
  std::vector<std::string> names;
  for (const auto& j : arm.joints) names.push_back(j.name);
  CHECK(MujocoJointNames(xml) == names);
  const MujocoInverseResponse r = MujocoInverseDynamics(xml, names, q, qd, qdd);
  double worst = 0.0;
  for (std::size_t k = 0; k < q.size(); ++k) {
    const Eigen::VectorXd tau = reference::ArmTorque(arm, q[k], qd[k], qdd[k]);
    for (std::size_t j = 0; j < 3; ++j) worst = std::max(worst, std::abs(r.control[j][k] - tau(static_cast<Eigen::Index>(j))));
  }
  INFO("largest difference " << worst << " N m");
  CHECK(worst < 1e-3);
}
