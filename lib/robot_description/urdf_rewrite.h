// A URDF rewritten with identified dynamics (docs/export.md#serial-robot):
// the user's file kept as written — visuals, meshes, transmissions, plugins
// and comments — with the named links' <inertial> replaced, other named
// links' <inertial> removed (their mass merged into a body that is
// written), and the named joints' <dynamics damping friction> set. Parsed
// and printed by TinyXML, which liburdfdom reads URDFs with.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace driveid {

struct UrdfLinkInertial {
  std::string link;
  double mass = 0.0;                                          ///< [kg]
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();           ///< in the link's frame [m]
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();          ///< about the centre [kg m^2]
  std::string comment;                                        ///< a comment placed before it
};

struct UrdfJointDynamics {
  std::string joint;
  double damping = 0.0, friction = 0.0;
  std::string comment;
};

struct UrdfRewrite {
  std::vector<std::string> header;  ///< comment lines after the XML declaration
  std::vector<UrdfLinkInertial> inertials;
  std::vector<std::string> removed;  ///< links whose <inertial> goes
  std::vector<UrdfJointDynamics> dynamics;
};

/// The rewritten text. Throws InputError naming `path` when the text is not
/// XML with a <robot> root, or a named link or joint is not in it.
std::string RewriteUrdf(const std::string& path, const std::string& text, const UrdfRewrite& rewrite);

}  // namespace driveid
