#include "robot_description/urdf_robot.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <Eigen/Geometry>
#include <console_bridge/console.h>
#include <fmt/format.h>
#include <urdf_parser/urdf_parser.h>

#include "core/errors.h"
#include "system/file_reading.h"

namespace driveid {
namespace {

// liburdfdom reports through console_bridge (to stderr by default): the
// library prints nothing, so its messages are caught and put in the error.
class CaughtMessages final : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) errors.push_back(text);
  }
  std::vector<std::string> errors;
};

class CatchMessages {
 public:
  explicit CatchMessages(CaughtMessages* to) { console_bridge::useOutputHandler(to); }
  ~CatchMessages() { console_bridge::restorePreviousOutputHandler(); }
  CatchMessages(const CatchMessages&) = delete;
  CatchMessages& operator=(const CatchMessages&) = delete;
};

// The XML parser recurses per nested element: a hostile file of deeply
// nested elements would exhaust the stack, so nesting is bounded first. A
// URDF nests a few levels (robot, link, inertial, origin).
constexpr int kMaxNesting = 64;

int NestingDepth(const std::string& text) {
  int depth = 0, deepest = 0;
  for (std::size_t i = 0; i + 1 < text.size(); ++i) {
    if (text[i] != '<') continue;
    const char next = text[i + 1];
    if (next == '/') {
      --depth;
    } else if (next != '?' && next != '!') {
      const std::size_t close = text.find('>', i);
      if (close == std::string::npos) break;
      if (text[close - 1] != '/') deepest = std::max(deepest, ++depth);
      i = close;
    }
  }
  return deepest;
}

RigidTransform FromPose(const urdf::Pose& pose) {
  RigidTransform t;
  const urdf::Rotation& r = pose.rotation;
  t.rotation = Eigen::Quaterniond(r.w, r.x, r.y, r.z).normalized().toRotationMatrix();
  t.translation = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return t;
}

bool Finite(const RigidTransform& t) { return t.rotation.allFinite() && t.translation.allFinite(); }

// The link's inertial in its own frame (zero without one).
InertialParameters LinkInertial(const std::string& path, const urdf::Link& link) {
  if (!link.inertial) return {};
  const urdf::Inertial& in = *link.inertial;
  Eigen::Matrix3d inertia;
  inertia << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
  const RigidTransform frame = FromPose(in.origin);
  if (!std::isfinite(in.mass) || in.mass < 0.0 || !inertia.allFinite() || !Finite(frame)) {
    throw InputError(fmt::format("{}: link '{}': its <inertial> needs a finite mass >= 0 and a finite inertia", path,
                                 link.name));
  }
  return InertialFromCentre(in.mass, frame.translation, frame.rotation * inertia * frame.rotation.transpose());
}

void Add(InertialParameters& to, const InertialParameters& from) {
  for (std::size_t k = 0; k < kInertialParameters; ++k) to[k] += from[k];
}

struct Placed {
  int body = -1;           // the joint whose body carries the link; -1: the base
  RigidTransform in_body;  // the link's frame in that body's frame
};

SerialJoint MakeJoint(const std::string& path, const urdf::Joint& j, const Placed& parent) {
  SerialJoint joint;
  joint.name = j.name;
  joint.body = j.child_link_name;
  joint.parent = parent.body;
  joint.type = j.type == urdf::Joint::PRISMATIC ? SerialJointType::kPrismatic : SerialJointType::kRevolute;
  joint.origin = Compose(parent.in_body, FromPose(j.parent_to_joint_origin_transform));
  const Eigen::Vector3d axis(j.axis.x, j.axis.y, j.axis.z);
  if (!axis.allFinite() || axis.norm() < 1e-9 || !Finite(joint.origin)) {
    throw InputError(fmt::format("{}: joint '{}': its <axis> must be a finite nonzero vector and its <origin> finite",
                                 path, j.name));
  }
  joint.axis = axis.normalized();
  if (j.limits) {
    if (j.type != urdf::Joint::CONTINUOUS && j.limits->upper > j.limits->lower) {
      joint.lower = j.limits->lower;
      joint.upper = j.limits->upper;
    }
    if (j.limits->velocity > 0.0) joint.velocity_limit = j.limits->velocity;
    if (j.limits->effort > 0.0) joint.effort_limit = j.limits->effort;
  }
  return joint;
}

// Each mimic joint's leader (through mimics of mimics: q = m1 (m2 q_l + o2)
// + o1), multiplier and offset; InputError for a leader that is no movable
// joint, a cycle, or a multiplier that is zero or not finite.
void ResolveMimics(const std::string& path, const std::vector<std::pair<std::size_t, urdf::JointMimicSharedPtr>>& mimics,
                   SerialRobot& robot) {
  std::map<std::string, std::size_t> index;
  for (std::size_t j = 0; j < robot.size(); ++j) index[robot.joints[j].name] = j;
  std::map<std::size_t, std::pair<std::size_t, urdf::JointMimicSharedPtr>> direct;
  for (const auto& [joint, mimic] : mimics) {
    const auto leader = index.find(mimic->joint_name);
    if (leader == index.end()) {
      throw InputError(fmt::format("{}: joint '{}' mimics '{}', which is no revolute, continuous or prismatic joint of "
                                   "the robot", path, robot.joints[joint].name, mimic->joint_name));
    }
    if (!std::isfinite(mimic->multiplier) || mimic->multiplier == 0.0 || !std::isfinite(mimic->offset)) {
      throw InputError(fmt::format("{}: joint '{}': its <mimic> multiplier must be finite and nonzero, its offset finite",
                                   path, robot.joints[joint].name));
    }
    direct[joint] = {leader->second, mimic};
  }
  for (const auto& [joint, first] : direct) {
    double multiplier = 1.0, offset = 0.0;
    std::size_t at = joint;
    for (std::size_t steps = 0; direct.count(at) != 0; ++steps) {
      if (steps > direct.size()) {
        throw InputError(fmt::format("{}: joint '{}': its <mimic> chain returns to itself", path, robot.joints[joint].name));
      }
      const auto& [leader, mimic] = direct.at(at);
      offset += multiplier * mimic->offset;
      multiplier *= mimic->multiplier;
      at = leader;
    }
    SerialJoint& j = robot.joints[joint];
    j.mimic = static_cast<int>(at);
    j.mimic_multiplier = multiplier;
    j.mimic_offset = offset;
  }
}

// A joint's <dynamics damping friction> as its drive's viscous and Coulomb
// friction (zero where absent).
SerialDriveParameters JointDynamics(const std::string& path, const urdf::Joint& j) {
  SerialDriveParameters d;
  if (!j.dynamics) return d;
  if (!std::isfinite(j.dynamics->damping) || !std::isfinite(j.dynamics->friction) || j.dynamics->damping < 0.0 ||
      j.dynamics->friction < 0.0) {
    throw InputError(fmt::format("{}: joint '{}': its <dynamics> damping and friction must be finite and >= 0", path,
                                 j.name));
  }
  d.viscous = j.dynamics->damping;
  d.coulomb = j.dynamics->friction;
  return d;
}

// Each joint's position among the file's <joint> elements: liburdfdom keeps
// a link's children in the order of their names, the user wrote them in
// this one.
std::map<std::string, std::size_t> JointFileOrder(const std::string& text) {
  std::map<std::string, std::size_t> order;
  for (std::size_t at = text.find("<joint"); at != std::string::npos; at = text.find("<joint", at + 1)) {
    const std::size_t end = text.find('>', at);
    const std::size_t name = text.find("name", at);
    if (end == std::string::npos || name == std::string::npos || name > end) continue;
    const std::size_t quote = text.find_first_of("\"'", name);
    if (quote == std::string::npos || quote > end) continue;
    const std::size_t close = text.find(text[quote], quote + 1);
    if (close == std::string::npos || close > end) continue;
    order.emplace(text.substr(quote + 1, close - quote - 1), order.size());
  }
  return order;
}

std::size_t FileIndex(const std::map<std::string, std::size_t>& order, const std::string& name) {
  const auto it = order.find(name);
  return it == order.end() ? order.size() : it->second;
}

}  // namespace

UrdfRobot ParseUrdfRobot(const std::string& path, const std::string& text) {
  if (NestingDepth(text) > kMaxNesting) {
    throw InputError(fmt::format("{}: elements nested deeper than {} levels: not a URDF", path, kMaxNesting));
  }
  CaughtMessages caught;
  urdf::ModelInterfaceSharedPtr model;
  {
    const CatchMessages catching(&caught);
    model = urdf::parseURDF(text);
  }
  // liburdfdom reports some malformed elements and goes on without them (an
  // <inertial> whose mass is not a number becomes a massless link): any
  // error it reports refuses the file.
  if (!model || !model->getRoot() || !caught.errors.empty()) {
    throw InputError(fmt::format("{}: not a URDF liburdfdom reads{}{}", path, caught.errors.empty() ? "" : ": ",
                                 fmt::join(caught.errors, "; ")));
  }
  UrdfRobot out;
  out.robot.name = model->getName();
  std::vector<std::string> on_base, merged;
  const std::map<std::string, std::size_t> order = JointFileOrder(text);
  // Depth first from the root without recursion (a hostile chain may be
  // long), siblings in the file's order: joints come out in preorder, each
  // after its parent, a chain's from base to tip.
  struct Pending {
    urdf::JointConstSharedPtr joint;
    Placed parent;
  };
  std::vector<Pending> stack;
  std::vector<std::pair<std::size_t, urdf::JointMimicSharedPtr>> mimics;
  const auto visit = [&](const urdf::Link& link, const Placed& here) {
    const InertialParameters own = LinkInertial(path, link);
    if (here.body < 0) {
      if (own[0] > 0.0) on_base.push_back(link.name);
    } else {
      Add(out.robot.bodies[static_cast<std::size_t>(here.body)], TransformInertial(own, here.in_body));
      SerialJoint& mover = out.robot.joints[static_cast<std::size_t>(here.body)];
      if (link.name != mover.body) {
        merged.push_back(link.name);
        mover.carried.push_back(link.name);
      }
    }
    std::vector<urdf::JointConstSharedPtr> children(link.child_joints.begin(), link.child_joints.end());
    std::sort(children.begin(), children.end(), [&](const auto& a, const auto& b) {
      return FileIndex(order, a->name) < FileIndex(order, b->name);
    });
    for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back({*it, here});
  };
  visit(*model->getRoot(), Placed{});
  while (!stack.empty()) {
    const Pending next = stack.back();
    stack.pop_back();
    const urdf::Joint& j = *next.joint;
    const urdf::LinkConstSharedPtr child = model->getLink(j.child_link_name);
    if (!child) throw InputError(fmt::format("{}: joint '{}' names no link '{}'", path, j.name, j.child_link_name));
    Placed placed;
    switch (j.type) {
      case urdf::Joint::FIXED:
        placed = {next.parent.body, Compose(next.parent.in_body, FromPose(j.parent_to_joint_origin_transform))};
        if (!Finite(placed.in_body)) throw InputError(fmt::format("{}: joint '{}': its <origin> is not finite", path, j.name));
        break;
      case urdf::Joint::REVOLUTE:
      case urdf::Joint::CONTINUOUS:
      case urdf::Joint::PRISMATIC:
        out.robot.joints.push_back(MakeJoint(path, j, next.parent));
        out.robot.bodies.push_back({});
        out.drives.push_back(JointDynamics(path, j));
        if (j.mimic) mimics.push_back({out.robot.joints.size() - 1, j.mimic});
        placed = {static_cast<int>(out.robot.joints.size()) - 1, RigidTransform{}};
        break;
      default:
        throw InputError(fmt::format("{}: joint '{}' is floating or planar: only revolute, continuous, prismatic and "
                                     "fixed joints are supported (a robot on a fixed base)",
                                     path, j.name));
    }
    visit(*child, placed);
  }
  if (out.robot.joints.empty()) throw InputError(fmt::format("{}: the URDF has no revolute or prismatic joint", path));
  ResolveMimics(path, mimics, out.robot);
  if (!on_base.empty()) {
    out.notes.push_back(fmt::format("{}: link(s) {} fixed to the base do not move: their inertials are left out", path,
                                    fmt::join(on_base, ", ")));
  }
  if (!merged.empty()) {
    out.notes.push_back(fmt::format("{}: link(s) {} are carried by fixed joints: merged into the body that moves them",
                                    path, fmt::join(merged, ", ")));
  }
  return out;
}

std::string ReadUrdfText(const std::string& path) {
  ReadLimits limits;
  limits.max_bytes = std::size_t{64} << 20;
  limits.max_line_bytes = 0;
  limits.max_bytes_hint = "a URDF may be at most 64 MiB";
  return ReadFileToString(path, limits);
}

UrdfRobot ReadUrdfRobot(const std::string& path) { return ParseUrdfRobot(path, ReadUrdfText(path)); }

}  // namespace driveid
