#include "export/serial_robot_export.h"

#include <cmath>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <fmt/format.h>

#include "core/errors.h"
#include "params/robot_coupling_section.h"
#include "params/serial_robot_section.h"
#include "robot_description/urdf_rewrite.h"
#include "models/serial_robot.h"

namespace driveid {
namespace {

using namespace export_text;

// The robot with the section's consistent bodies and drives, each matched
// to its joint by name.
struct IdentifiedArm {
  SerialRobot robot;  // bodies: the identified ones
  std::vector<SerialDriveParameters> drives;
  std::string urdf_path, urdf_text;
};

IdentifiedArm Identified(const ParameterFile& file, const ExportOptions& o) {
  const SerialRobotSection& s = *file.Find<SerialRobotSection>();
  if (s.bodies.empty() || s.drives.empty()) {
    throw InputError(fmt::format("{}: serial_robot has no bodies and drives (the physically consistent parameters, "
                                 "docs/models.md#physical-consistency): refit with drivetrain-fit robot ‹urdf›",
                                 o.source));
  }
  if (file.Find<RobotCouplingSection>() != nullptr) {
    throw InputError(fmt::format("{}: the robot's drives are coupled (robot.coupling): URDF and MJCF hold a joint's own "
                                 "armature and friction, not a motor's that turns two joints; not exported yet",
                                 o.source));
  }
  SectionUrdf urdf = ReadSectionUrdf(s, o.urdf, o.source);
  IdentifiedArm arm{std::move(urdf.robot), {}, std::move(urdf.path), std::move(urdf.text)};
  const std::size_t n = arm.robot.size();
  if (s.bodies.size() != n || s.drives.size() != n) {
    throw InputError(fmt::format("{}: serial_robot has {} bodies and {} drives, the URDF's robot {} joints: written for "
                                 "another robot", o.source, s.bodies.size(), s.drives.size(), n));
  }
  arm.drives.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    const SerialJoint& joint = arm.robot.joints[j];
    if (s.bodies[j].link != joint.body || s.drives[j].joint != joint.name) {
      throw InputError(fmt::format("{}: serial_robot's body {} / drive {} is not the URDF's link '{}' / joint '{}': "
                                   "written for another robot", o.source, s.bodies[j].link, s.drives[j].joint,
                                   joint.body, joint.name));
    }
    const InertialParameters& p = s.bodies[j].parameters;
    if (!(p[0] > 0.0)) throw InputError(fmt::format("{}: body {} has mass {}: not a body a simulator takes", o.source, joint.body, p[0]));
    arm.robot.bodies[j] = p;
    arm.drives[j] = s.drives[j].drive;
    if (s.drives[j].drive.viscous_asymmetry != 0.0) {
      throw InputError(fmt::format("{}: joint {}'s viscous friction differs per direction (viscous_asymmetry {:.4g}): "
                                   "URDF and MJCF hold one damping per joint; refit without ‹per_direction› to export",
                                   o.source, joint.name, s.drives[j].drive.viscous_asymmetry));
    }
  }
  return arm;
}

// Centre and inertia about the centre of a body's standard parameters.
struct CentralInertial {
  double mass = 0.0;
  Eigen::Vector3d centre;
  Eigen::Matrix3d inertia;
};

// A consistent body may lie on the boundary of the physical set (a
// principal moment equal to the sum of the other two: a rod or a plate),
// which simulators check with no tolerance (MuJoCo: "A + B >= C"): there
// the moments are raised by kInertiaMargin of their sum, and `nudged` says so.
constexpr double kInertiaMargin = 1e-9;

CentralInertial Central(const InertialParameters& p, bool* nudged = nullptr) {
  CentralInertial c;
  c.mass = p[0];
  c.centre = Eigen::Vector3d(p[1], p[2], p[3]) / p[0];
  c.inertia = InertiaMatrix(p) - c.mass * (c.centre.squaredNorm() * Eigen::Matrix3d::Identity() - c.centre * c.centre.transpose());
  c.inertia = 0.5 * (c.inertia + c.inertia.transpose());
  const Eigen::Vector3d moments = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(c.inertia).eigenvalues();  // ascending
  const double sum = moments.sum();
  const double deficit = std::max(moments(2) - moments(0) - moments(1), -moments(0));
  if (deficit > -kInertiaMargin * sum) {
    c.inertia += (std::max(deficit, 0.0) + kInertiaMargin * std::max(sum, 0.0)) * Eigen::Matrix3d::Identity();
    if (nudged) *nudged = true;
  }
  return c;
}

std::string Unit(const SerialJoint& j, const char* rotary, const char* linear) {
  return j.type == SerialJointType::kPrismatic ? linear : rotary;
}

std::string ExportUrdf(const IdentifiedArm& arm, const ExportOptions& o) {
  UrdfRewrite w;
  w.header = {CommentText("driveid export of " + o.source + " (docs/export.md#serial-robot)"),
              CommentText("made by: " + o.command),
              "inertials: the physically consistent fit (docs/models.md#physical-consistency); the data determine "
              "only their base combinations, the fit's file lists them with std",
              "URDF has no armature (rotor inertia) and no torque offset: each joint's are in a comment beside it"};
  for (std::size_t j = 0; j < arm.robot.size(); ++j) {
    const SerialJoint& joint = arm.robot.joints[j];
    bool nudged = false;
    const CentralInertial c = Central(arm.robot.bodies[j], &nudged);
    std::string note = "identified by driveid";
    if (nudged) note += fmt::format("; on the triangle inequality's boundary: principal moments raised by {:g} of their sum", kInertiaMargin);
    if (!joint.carried.empty()) note += "; carries the merged link(s) " + fmt::format("{}", fmt::join(joint.carried, ", "));
    w.inertials.push_back({joint.body, c.mass, c.centre, c.inertia, CommentText(note)});
    for (const std::string& link : joint.carried) w.removed.push_back(link);
    const SerialDriveParameters& d = arm.drives[j];
    w.dynamics.push_back(
        {joint.name, d.viscous, d.coulomb,
         CommentText(fmt::format("identified by driveid: armature {} {}, offset {} {} (not URDF fields)",
                                 Number(d.armature), Unit(joint, "kg m^2", "kg"), Number(d.offset),
                                 Unit(joint, "N m", "N")))});
  }
  return RewriteUrdf(arm.urdf_path, arm.urdf_text, w);
}

std::string Triple(const Eigen::Vector3d& v) { return Number(v.x()) + " " + Number(v.y()) + " " + Number(v.z()); }

std::string ExportMjcf(const IdentifiedArm& arm, const ExportOptions& o) {
  const SerialRobot& r = arm.robot;
  for (const SerialJoint& j : r.joints) {
    if (j.mimic >= 0) {
      throw InputError(fmt::format("{}: joint '{}' mimics '{}': an MJCF of mimic joints (an equality constraint, no "
                                   "actuator of its own) is not exported yet; export to urdf",
                                   o.source, j.name, r.joints[static_cast<std::size_t>(j.mimic)].name));
    }
  }
  std::string out = fmt::format("<mujoco model=\"{}\">\n", XmlAttribute(r.name.empty() ? "driveid_robot" : r.name));
  out += Provenance(o, "  <!--", " -->");
  out += "  <!-- bodies from " + CommentText(arm.urdf_path) +
         " with the physically consistent inertials (docs/models.md#physical-consistency); each actuator's ctrl is "
         "the joint's logged torque [N m or N] -->\n";
  out += "  <compiler angle=\"radian\" autolimits=\"true\"/>\n";
  out += MjcfOptionLines();
  out += "  <worldbody>\n";
  // Bodies nest in the joints' preorder: close a body when the next joint's
  // parent is not it.
  std::vector<int> open;
  const auto close_to = [&](int parent) {
    while (!open.empty() && open.back() != parent) {
      out += std::string(2 * (open.size() + 1), ' ') + "</body>\n";
      open.pop_back();
    }
  };
  for (std::size_t j = 0; j < r.size(); ++j) {
    const SerialJoint& joint = r.joints[j];
    close_to(joint.parent);
    const std::string pad(2 * (open.size() + 2), ' ');
    const Eigen::Quaterniond q(joint.origin.rotation);
    out += fmt::format("{}<body name=\"{}\" pos=\"{}\" quat=\"{} {} {} {}\">\n", pad, XmlAttribute(joint.body), Triple(joint.origin.translation),
                       Number(q.w()), Number(q.x()), Number(q.y()), Number(q.z()));
    const SerialDriveParameters& d = arm.drives[j];
    std::string range;
    if (std::isfinite(joint.lower) && std::isfinite(joint.upper)) range = fmt::format(" range=\"{} {}\"", Number(joint.lower), Number(joint.upper));
    out += fmt::format("{}  <joint name=\"{}\" type=\"{}\" axis=\"{}\"{} armature=\"{}\" damping=\"{}\" frictionloss=\"{}\" "
                       "solreffriction=\"{} 1\"/>\n",
                       pad, XmlAttribute(joint.name), joint.type == SerialJointType::kPrismatic ? "slide" : "hinge", Triple(joint.axis),
                       range, Number(d.armature), Number(d.viscous), Number(d.coulomb), Number(2.0 * kMjcfTimestep));
    bool nudged = false;
    const CentralInertial c = Central(r.bodies[j], &nudged);
    const Eigen::Matrix3d& i = c.inertia;
    if (nudged) {
      out += fmt::format("{}  <!-- on the triangle inequality's boundary: principal moments raised by {:g} of their sum -->\n",
                         pad, kInertiaMargin);
    }
    out += fmt::format("{}  <inertial pos=\"{}\" mass=\"{}\" fullinertia=\"{} {} {} {} {} {}\"/>\n", pad, Triple(c.centre),
                       Number(c.mass), Number(i(0, 0)), Number(i(1, 1)), Number(i(2, 2)), Number(i(0, 1)), Number(i(0, 2)),
                       Number(i(1, 2)));
    open.push_back(static_cast<int>(j));
  }
  close_to(-1);
  out += "  </worldbody>\n  <actuator>\n    <!-- force = ctrl - tau_0: ctrl is the logged torque -->\n";
  for (std::size_t j = 0; j < r.size(); ++j) {
    const std::string name = XmlAttribute(r.joints[j].name);
    out += fmt::format("    <general name=\"{}_motor\" joint=\"{}\" gainprm=\"1\" biastype=\"affine\" biasprm=\"{} 0 0\"/>\n",
                       name, name, Number(arm.drives[j].offset == 0.0 ? 0.0 : -arm.drives[j].offset));
  }
  out += "  </actuator>\n</mujoco>\n";
  return out;
}

}  // namespace

std::string ExportSerialRobot(const ParameterFile& file, ExportTarget target, const ExportOptions& options) {
  if (target != ExportTarget::kUrdf && target != ExportTarget::kMjcf) {
    throw InputError(fmt::format("a serial robot exports to {} (docs/export.md#serial-robot), not {}",
                                 ListExportTargets({ExportTarget::kUrdf, ExportTarget::kMjcf}), ExportTargetName(target)));
  }
  const IdentifiedArm arm = Identified(file, options);
  return target == ExportTarget::kUrdf ? ExportUrdf(arm, options) : ExportMjcf(arm, options);
}

}  // namespace driveid
