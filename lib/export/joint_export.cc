#include "export/joint_export.h"

#include <cctype>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "core/errors.h"
#include "export/export_text.h"
#include "export/feedback_export.h"
#include "models/joint.h"

namespace driveid {
namespace {

using namespace export_text;

struct JointView {
  JointParameters p;
  double gear = 0.0;
};

JointView ViewJoint(const JointSection& s) {
  JointView v;
  for (const auto& row : JointParameterTable()) {
    if (row.in_model != nullptr) v.p.*(row.in_model) = (s.*(row.in_section)).value_or(0.0);
  }
  v.gear = s.gear_ratio.value_or(0.0);
  std::vector<std::string> missing;
  if (!(v.gear > 0.0)) missing.push_back("joint.gear_ratio");
  if (!(v.p.motor_inertia > 0.0)) missing.push_back("joint.motor_inertia");
  if (!(v.p.link_inertia > 0.0)) missing.push_back("joint.link_inertia");
  if (!(v.p.stiffness > 0.0)) missing.push_back("joint.stiffness");
  if (!missing.empty()) {
    std::string names;
    for (const std::string& m : missing) names += (names.empty() ? "" : ", ") + m;
    throw InputError(fmt::format("{}: a simulator model of the elastic joint needs these > 0 (fit them, or give them)",
                                 names));
  }
  RequireExportInertia("joint.motor_inertia", v.p.motor_inertia);
  RequireExportInertia("joint.link_inertia", v.p.link_inertia);
  return v;
}

// One comment line per joint value with its std from the fit section.
std::string ValueComments(const ParameterFile& file, const JointView& v, const std::string& open,
                          const std::string& close) {
  std::string out;
  for (const auto& row : JointParameterTable()) {
    if (row.in_model == nullptr) continue;
    out += open + " " +
           CommentText(fmt::format("{}: {}", row.spec.symbol, WithStd(file, row.spec.key, v.p.*(row.in_model), row.spec.unit))) +
           close + "\n";
  }
  return out;
}

std::string Mjcf(const ParameterFile& file, const JointView& v, const ExportOptions& o) {
  const GravityBody g = MakeGravityBody(v.p.link_inertia, v.p.gravity_cos, v.p.gravity_sin);
  const double motor_own = OwnBodyInertia(v.p.motor_inertia), link_own = OwnBodyInertia(v.p.link_inertia);
  const double link_body = link_own + g.mass * g.radius * g.radius;
  std::string out = "<mujoco model=\"driveid_" + o.joint + "\">\n";
  out += Provenance(o, "  <!--", " -->");
  out += "  <!-- elastic joint, link side (docs/models.md#elastic-joint): motor joint " + o.joint + "_motor = theta_m = "
         "q_motor / n, link joint " + o.joint + " = theta_l, spring as a fixed tendon theta_m - theta_l -->\n";
  out += ValueComments(file, v, "  <!--", " -->");
  out += fmt::format("  <!-- gear ratio n = {} -->\n", Number(v.gear));
  if (v.p.link_torque_offset != 0.0) out += "  <!-- link_torque_offset belongs to the shaft-torque sensor: not a model force -->\n";
  out += MjcfOptionLines();
  const std::string joint_line =
      "      <joint name=\"{}\" type=\"hinge\" axis=\"0 -1 0\" armature=\"{}\" damping=\"{}\" frictionloss=\"{}\" "
      "solreffriction=\"{} 1\"/>\n";
  out += "  <worldbody>\n";
  out += fmt::format("    <body name=\"{}_rotor\">\n", o.joint);
  out += fmt::format(fmt::runtime(joint_line), o.joint + "_motor", Number(v.p.motor_inertia - motor_own),
                     Number(v.p.motor_viscous), Number(v.p.motor_coulomb), Number(2.0 * kMjcfTimestep));
  out += fmt::format("      <inertial pos=\"0 0 0\" mass=\"{0}\" diaginertia=\"{0} {0} {0}\"/>\n    </body>\n",
                     Number(motor_own));
  out += fmt::format("    <body name=\"{}_link\">\n", o.joint);
  out += fmt::format(fmt::runtime(joint_line), o.joint, Number(v.p.link_inertia - link_body), Number(v.p.link_viscous),
                     Number(v.p.link_coulomb), Number(2.0 * kMjcfTimestep));
  out += fmt::format("      <inertial pos=\"{} 0 {}\" mass=\"{}\" diaginertia=\"{} {} {}\"/>\n    </body>\n", Number(g.x),
                     Number(g.z), Number(g.mass > 0.0 ? g.mass : link_own), Number(link_own), Number(link_own),
                     Number(link_own));
  out += "  </worldbody>\n  <tendon>\n";
  out += fmt::format("    <fixed name=\"{0}_spring\" stiffness=\"{1}\" damping=\"{2}\" springlength=\"0\">\n"
                     "      <joint joint=\"{0}_motor\" coef=\"1\"/>\n      <joint joint=\"{0}\" coef=\"-1\"/>\n"
                     "    </fixed>\n  </tendon>\n",
                     o.joint, Number(v.p.stiffness), Number(v.p.damping));
  out += "  <actuator>\n";
  out += fmt::format("    <!-- torque on theta_m = n (ctrl - tau_0 / n) = n ctrl - tau_0: ctrl is the logged motor torque -->\n");
  out += fmt::format("    <general name=\"{0}_drive\" joint=\"{0}_motor\" gear=\"{1}\" gainprm=\"1\" biastype=\"affine\" "
                     "biasprm=\"{2} 0 0\"/>\n  </actuator>\n</mujoco>\n",
                     o.joint, Number(v.gear), Number(v.p.offset == 0.0 ? 0.0 : -v.p.offset / v.gear));
  return out;
}

std::string Urdf(const ParameterFile& file, const JointView& v, const ExportOptions& o) {
  const GravityBody g = MakeGravityBody(v.p.link_inertia, v.p.gravity_cos, v.p.gravity_sin);
  std::string out = "<?xml version=\"1.0\"?>\n";
  out += Provenance(o, "<!--", " -->");
  out += "<!-- URDF has no joint elasticity and no rotor: the link's joint holds b_l and c_l and the link J_l; the "
         "motor side (J_m, b_m, c_m, tau_0), the gear, the stiffness k and damping d are not held (the MJCF holds "
         "them) -->\n";
  out += ValueComments(file, v, "<!--", " -->");
  out += fmt::format("<robot name=\"driveid_{0}\">\n  <link name=\"base\"/>\n  <link name=\"{0}_link\">\n", o.joint);
  const double mass = g.mass > 0.0 ? g.mass : OwnBodyInertia(v.p.link_inertia);
  out += fmt::format("    <inertial>\n      <origin xyz=\"{} 0 {}\"/>\n      <mass value=\"{}\"/>\n", Number(g.x),
                     Number(g.z), Number(mass));
  out += fmt::format("      <inertia ixx=\"{0}\" ixy=\"0\" ixz=\"0\" iyy=\"{0}\" iyz=\"0\" izz=\"{0}\"/>\n    </inertial>\n"
                     "  </link>\n",
                     Number(v.p.link_inertia - g.mass * g.radius * g.radius));
  out += fmt::format("  <joint name=\"{0}\" type=\"continuous\">\n    <parent link=\"base\"/>\n    <child link=\"{0}_link\"/>\n"
                     "    <axis xyz=\"0 -1 0\"/>\n    <dynamics damping=\"{1}\" friction=\"{2}\"/>\n  </joint>\n</robot>\n",
                     o.joint, Number(v.p.link_viscous), Number(v.p.link_coulomb));
  return out;
}

std::string CHeader(const ParameterFile& file, const JointView& v, const ExportOptions& o) {
  const std::string upper = UpperCase(o.joint);
  std::string out = CHeaderOpen(o, upper, "/* elastic joint, link side (docs/models.md#elastic-joint) */\n");
  out += fmt::format("DRIVEID_CONSTANT {}_gear_ratio = {};  /* n */\n", upper, Number(v.gear));
  for (const auto& row : JointParameterTable()) {
    if (row.in_model == nullptr) continue;
    out += fmt::format("DRIVEID_CONSTANT {}_{} = {};  /* {}, {} */\n", upper, row.spec.key, Number(v.p.*(row.in_model)),
                       CommentText(row.spec.symbol), CommentText(row.spec.unit));
    for (const ParameterEstimate& e : file.fit_estimates) {
      if (e.name == row.spec.key) out += fmt::format("DRIVEID_CONSTANT {}_{}_STD = {:.6g};\n", upper, row.spec.key, e.standard_error);
    }
  }
  out += FeedbackCHeaderLines(file.feedback, upper);
  out += CHeaderClose(upper);
  return out;
}

}  // namespace

std::string ExportJoint(const JointSection& joint, const ParameterFile& file, ExportTarget target,
                        const ExportOptions& options) {
  switch (target) {
    case ExportTarget::kMjcf: return Mjcf(file, ViewJoint(joint), options);
    case ExportTarget::kUrdf: return Urdf(file, ViewJoint(joint), options);
    case ExportTarget::kCHeader: return CHeader(file, ViewJoint(joint), options);
    case ExportTarget::kWpilibJava:
    case ExportTarget::kWpilibCpp:
    case ExportTarget::kJson: break;
  }
  throw InputError(fmt::format("the elastic joint has no feed-forward section: export it to {} "
                               "(docs/export.md#elastic-joint)",
                               ListExportTargets({ExportTarget::kMjcf, ExportTarget::kUrdf, ExportTarget::kCHeader})));
}

}  // namespace driveid
