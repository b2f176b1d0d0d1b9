#include "support/reference_arm_urdf.h"

#include <sstream>

#include <Eigen/Geometry>

namespace reference {

std::string ArmUrdf(const Arm& arm, bool extras) {
  std::ostringstream urdf;
  urdf.precision(17);
  urdf << "<?xml version=\"1.0\"?>\n<!-- the reference arm -->\n<robot name=\"arm3\">\n  <link name=\"base\"/>\n";
  for (const auto& j : arm.joints) {
    const Eigen::Matrix3d& i = j.inertia_at_centre;
    urdf << "  <link name=\"" << j.body << "\">\n";
    if (extras) urdf << "    <visual><geometry><mesh filename=\"package://arm/" << j.body << ".stl\"/></geometry></visual>\n";
    urdf << "    <inertial><origin xyz=\"" << j.centre.x() << ' ' << j.centre.y() << ' ' << j.centre.z()
         << "\" rpy=\"0 0 0\"/><mass value=\"" << j.mass << "\"/>\n      <inertia ixx=\"" << i(0, 0) << "\" ixy=\""
         << i(0, 1) << "\" ixz=\"" << i(0, 2) << "\" iyy=\"" << i(1, 1) << "\" iyz=\"" << i(1, 2) << "\" izz=\""
         << i(2, 2) << "\"/></inertial>\n  </link>\n";
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
  if (extras) {
    urdf << "  <link name=\"tool\">\n    <inertial><origin xyz=\"" << kToolCentreX << " 0 0\"/><mass value=\"" << kToolMass
         << "\"/><inertia ixx=\"" << kToolInertia << "\" ixy=\"0\" ixz=\"0\" iyy=\"" << kToolInertia
         << "\" iyz=\"0\" izz=\"" << kToolInertia << "\"/></inertial>\n  </link>\n";
    urdf << "  <joint name=\"tool_mount\" type=\"fixed\">\n    <parent link=\"" << arm.joints.back().body
         << "\"/><child link=\"tool\"/>\n    <origin xyz=\"" << kToolOffsetX << " 0 0\"/>\n  </joint>\n";
    urdf << "  <transmission name=\"" << arm.joints.front().name << "_transmission\"><type>transmission_interface/"
            "SimpleTransmission</type></transmission>\n";
  }
  urdf << "</robot>\n";
  return urdf.str();
}

}  // namespace reference
