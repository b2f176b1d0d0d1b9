// Writes the reference three-joint arm (tests/support/reference_serial_arm.h)
// as a URDF and one of its logs as CSV (t, q_<joint>, tau_<joint>), for the
// command-line tests of `drivetrain-fit robot --urdf`.
// Usage: serial_arm_log ARM.urdf LOG.csv [seed [joints (3 or 6) [rate Hz [duration s]]]]
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include <Eigen/Geometry>

#include "support/reference_serial_arm.h"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: serial_arm_log ARM.urdf LOG.csv [seed [joints [rate [duration]]]]\n");
    return 2;
  }
  const reference::Arm arm =
      argc > 4 && std::atoi(argv[4]) == 6 ? reference::SixJointArm() : reference::ThreeJointArm();
  std::ofstream urdf(argv[1]);
  urdf.precision(17);
  urdf << "<?xml version=\"1.0\"?>\n<robot name=\"arm3\">\n  <link name=\"base\"/>\n";
  for (const auto& j : arm.joints) {
    const Eigen::Matrix3d& i = j.inertia_at_centre;
    urdf << "  <link name=\"" << j.body << "\">\n    <inertial><origin xyz=\"" << j.centre.x() << ' ' << j.centre.y()
         << ' ' << j.centre.z() << "\" rpy=\"0 0 0\"/><mass value=\"" << j.mass << "\"/>\n      <inertia ixx=\""
         << i(0, 0) << "\" ixy=\"" << i(0, 1) << "\" ixz=\"" << i(0, 2) << "\" iyy=\"" << i(1, 1) << "\" iyz=\""
         << i(1, 2) << "\" izz=\"" << i(2, 2) << "\"/></inertial>\n  </link>\n";
  }
  for (const auto& j : arm.joints) {
    const Eigen::Vector3d ypr = j.rotation.eulerAngles(2, 1, 0);
    const std::string parent = j.parent < 0 ? "base" : arm.joints[static_cast<std::size_t>(j.parent)].body;
    urdf << "  <joint name=\"" << j.name << "\" type=\"revolute\">\n    <parent link=\"" << parent
         << "\"/><child link=\"" << j.body << "\"/>\n    <origin xyz=\"" << j.translation.x() << ' '
         << j.translation.y() << ' ' << j.translation.z() << "\" rpy=\"" << ypr(2) << ' ' << ypr(1) << ' ' << ypr(0)
         << "\"/>\n    <axis xyz=\"" << j.axis.x() << ' ' << j.axis.y() << ' ' << j.axis.z()
         << "\"/>\n    <limit lower=\"-3\" upper=\"3\" effort=\"200\" velocity=\"3\"/>\n  </joint>\n";
  }
  urdf << "</robot>\n";
  reference::ArmLogOptions o;
  if (argc > 3) o.seed = static_cast<unsigned>(std::atoi(argv[3]));
  if (argc > 5) o.rate = std::atof(argv[5]);
  if (argc > 6) o.duration = std::atof(argv[6]);
  const reference::ArmLog log = reference::SimulateArm(arm, o);
  std::ofstream csv(argv[2]);
  csv.precision(10);
  csv << "t";
  for (const auto& j : arm.joints) csv << ",q_" << j.name << ",tau_" << j.name;
  csv << '\n';
  for (std::size_t k = 0; k < log.t.size(); ++k) {
    csv << log.t[k];
    for (std::size_t j = 0; j < arm.joints.size(); ++j) csv << ',' << log.q[j][k] << ',' << log.tau[j][k];
    csv << '\n';
  }
  return urdf && csv ? 0 : 1;
}
