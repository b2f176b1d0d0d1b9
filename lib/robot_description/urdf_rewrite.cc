#include "robot_description/urdf_rewrite.h"

#include <map>

#include <fmt/format.h>
#include <tinyxml.h>

#include "core/errors.h"

namespace driveid {
namespace {

// A number as the parameter file writes it: the shortest text that reads back exactly.
std::string Number(double value) { return fmt::format("{}", value); }

std::string Triple(double x, double y, double z) { return Number(x) + " " + Number(y) + " " + Number(z); }

// The robot's direct children named `tag`, by their name attribute.
std::map<std::string, TiXmlElement*> Children(TiXmlElement* robot, const char* tag) {
  std::map<std::string, TiXmlElement*> out;
  for (TiXmlElement* e = robot->FirstChildElement(tag); e != nullptr; e = e->NextSiblingElement(tag)) {
    const char* name = e->Attribute("name");
    if (name != nullptr) out.emplace(name, e);
  }
  return out;
}

// Removes every child `tag` of `parent`; returns the node that followed the
// first one removed (where a replacement goes), or null.
TiXmlNode* RemoveChildren(TiXmlElement* parent, const char* tag) {
  TiXmlNode* after = nullptr;
  bool first = true;
  while (TiXmlElement* child = parent->FirstChildElement(tag)) {
    if (first) after = child->NextSibling();
    first = false;
    parent->RemoveChild(child);
  }
  return after;
}

void InsertBefore(TiXmlElement* parent, TiXmlNode* before, const TiXmlNode& node) {
  if (before != nullptr) parent->InsertBeforeChild(before, node);
  else parent->InsertEndChild(node);
}

TiXmlElement InertialElement(const UrdfLinkInertial& l) {
  TiXmlElement inertial("inertial");
  TiXmlElement origin("origin");
  origin.SetAttribute("xyz", Triple(l.centre.x(), l.centre.y(), l.centre.z()));
  origin.SetAttribute("rpy", "0 0 0");
  inertial.InsertEndChild(origin);
  TiXmlElement mass("mass");
  mass.SetAttribute("value", Number(l.mass));
  inertial.InsertEndChild(mass);
  TiXmlElement inertia("inertia");
  const Eigen::Matrix3d& i = l.inertia;
  const char* keys[6] = {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"};
  const double values[6] = {i(0, 0), i(0, 1), i(0, 2), i(1, 1), i(1, 2), i(2, 2)};
  for (int k = 0; k < 6; ++k) inertia.SetAttribute(keys[k], Number(values[k]));
  inertial.InsertEndChild(inertia);
  return inertial;
}

}  // namespace

std::string RewriteUrdf(const std::string& path, const std::string& text, const UrdfRewrite& rewrite) {
  TiXmlDocument doc;
  doc.Parse(text.c_str(), nullptr, TIXML_ENCODING_UTF8);
  TiXmlElement* robot = doc.Error() ? nullptr : doc.RootElement();
  if (robot == nullptr || std::string(robot->Value()) != "robot") {
    throw InputError(fmt::format("{}: not a URDF (no <robot> element{}{})", path, doc.Error() ? ": " : "",
                                 doc.Error() ? doc.ErrorDesc() : ""));
  }
  const std::map<std::string, TiXmlElement*> links = Children(robot, "link");
  const std::map<std::string, TiXmlElement*> joints = Children(robot, "joint");
  const auto find = [&](const std::map<std::string, TiXmlElement*>& in, const std::string& name, const char* what) {
    const auto it = in.find(name);
    if (it == in.end()) throw InputError(fmt::format("{}: no <{} name=\"{}\">: not the URDF the robot was fitted on", path, what, name));
    return it->second;
  };
  for (const UrdfLinkInertial& l : rewrite.inertials) {
    TiXmlElement* link = find(links, l.link, "link");
    TiXmlNode* before = RemoveChildren(link, "inertial");
    if (!l.comment.empty()) InsertBefore(link, before, TiXmlComment((" " + l.comment + " ").c_str()));
    InsertBefore(link, before, InertialElement(l));
  }
  for (const std::string& name : rewrite.removed) RemoveChildren(find(links, name, "link"), "inertial");
  for (const UrdfJointDynamics& d : rewrite.dynamics) {
    TiXmlElement* joint = find(joints, d.joint, "joint");
    TiXmlNode* before = RemoveChildren(joint, "dynamics");
    if (!d.comment.empty()) InsertBefore(joint, before, TiXmlComment((" " + d.comment + " ").c_str()));
    TiXmlElement dynamics("dynamics");
    dynamics.SetAttribute("damping", Number(d.damping));
    dynamics.SetAttribute("friction", Number(d.friction));
    InsertBefore(joint, before, dynamics);
  }
  // The header's comments go first, after the declaration if there is one.
  TiXmlNode* first = doc.FirstChild();
  while (first != nullptr && first->ToDeclaration() != nullptr) first = first->NextSibling();
  for (const std::string& line : rewrite.header) {
    const TiXmlComment comment((" " + line + " ").c_str());
    if (first != nullptr) doc.InsertBeforeChild(first, comment);
    else doc.InsertEndChild(comment);
  }
  TiXmlPrinter printer;
  printer.SetIndent("  ");
  doc.Accept(&printer);
  std::string out = printer.Str();
  if (doc.FirstChild() == nullptr || doc.FirstChild()->ToDeclaration() == nullptr) out = "<?xml version=\"1.0\"?>\n" + out;
  return out;
}

}  // namespace driveid
