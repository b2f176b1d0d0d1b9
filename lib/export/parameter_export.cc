#include "export/parameter_export.h"

#include <cctype>
#include <cmath>
#include <optional>
#include <vector>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"
#include "params/serial_robot_section.h"
#include "export/export_text.h"
#include "export/feedback_export.h"
#include "export/joint_export.h"
#include "export/serial_robot_export.h"
#include "export/wpilib_export.h"
#include "models/axis.h"
#include "models/axis_term.h"
#include "models/feedforward.h"
#include "report/json.h"

namespace driveid {
namespace {

using namespace export_text;

// The axis as the exports see it: friction averaged over the directions
// where it was fitted per direction (a simulator joint has one value).
struct AxisView {
  AxisParameters p;
  bool linear = false;
  double damping = 0.0;       // b + (b+ + b-) / 2
  double friction = 0.0;      // tau_c + (tau_c+ + tau_c-) / 2
  double gravity = 0.0;       // Kg = hypot(g_c, g_s)
  double gravity_angle = 0.0;  // atan2(g_s, g_c)
  bool per_direction = false;
};

AxisView ViewAxis(const ParameterFile& file) {
  const AxisSection* section = file.Find<AxisSection>();
  if (!section) {
    throw InputError("no 'axis' or 'joint' section: export takes the parameter file of an axis or an elastic-joint "
                     "fit; a serial robot (serial_robot section) exports to urdf and mjcf; the drive train, planar robot and C-drive have no export target yet (docs/export.md)");
  }
  AxisView v;
  const AxisSection& a = *section;
  v.p = ModelValuesOr(AxisParameterTable(), a, 0.0);  // a term not given is 0 (models/axis.h)
  v.linear = section->linear;
  v.per_direction = v.p.coulomb_pos != 0.0 || v.p.coulomb_neg != 0.0 || v.p.viscous_pos != 0.0 || v.p.viscous_neg != 0.0;
  v.damping = v.p.viscous + 0.5 * (v.p.viscous_pos + v.p.viscous_neg);
  v.friction = v.p.coulomb + 0.5 * (v.p.coulomb_pos + v.p.coulomb_neg);
  v.gravity = std::hypot(v.p.gravity_cos, v.p.gravity_sin);
  v.gravity_angle = std::atan2(v.p.gravity_sin, v.p.gravity_cos);
  return v;
}

// What `target` says of the terms present that it cannot hold
// (models/axis_term.h ExportNote), one note each.
std::vector<std::string> TermNotes(const AxisView& v, AxisExportTarget target) {
  std::vector<std::string> out;
  const AxisValues values = AxisValuesOf(v.p);
  for (const AxisTerm* term : AxisTerms()) {
    const std::string note = term->ExportNote(target);
    if (!note.empty() && term->Present(&values[AxisFirstIndex(*term)])) out.push_back(note);
  }
  return out;
}

void RequireInertia(const AxisView& v) { RequireExportInertia("axis.inertia", v.p.inertia); }

// What a simulator joint cannot hold, one comment line each.
std::vector<std::string> NotRepresented(const AxisView& v, bool has_offset_channel) {
  std::vector<std::string> out;
  if (v.per_direction) out.push_back("direction-dependent friction: the mean of the two directions is written");
  for (const std::string& note : TermNotes(v, AxisExportTarget::kSimulator)) out.push_back(note);
  if (v.p.offset != 0.0 && !has_offset_channel) out.push_back("offset tau_0: add it to the commanded effort");
  return out;
}

GravityBody MakeGravityBody(const AxisView& v) {
  if (v.linear) return {};
  return export_text::MakeGravityBody(v.p.inertia, v.p.gravity_cos, v.p.gravity_sin);
}

std::string ExportMjcf(const ParameterFile& file, const ExportOptions& o) {
  const AxisView v = ViewAxis(file);
  RequireInertia(v);
  const GravityBody g = MakeGravityBody(v);
  // Units: the log's, as the feed-forward section names them (V for SysId
  // logs), else the axis model's SI units.
  const Feedforward& ff = file.feedforward;
  const bool log_units = !ff.effort_unit.empty() && !ff.position_unit.empty();
  const std::string force = log_units ? ff.effort_unit : v.linear ? "N" : "N m";
  const std::string unit = log_units ? FeedforwardUnit("Ka", ff.effort_unit, ff.position_unit) : v.linear ? "kg" : "kg m^2";
  const std::string rate = log_units ? FeedforwardUnit("Kv", ff.effort_unit, ff.position_unit)
                                     : v.linear ? "N s/m" : "N m s/rad";
  // The body's own inertia about the axis: tiny, plus the gravity mass's m r^2.
  const double own = OwnBodyInertia(v.p.inertia);
  const double body_inertia = v.linear ? 0.0 : own + g.mass * g.radius * g.radius;
  const double body_mass = v.linear ? own : (g.mass > 0.0 ? g.mass : own);
  const double armature = v.p.inertia - body_inertia - (v.linear ? body_mass : 0.0);
  std::string out = "<mujoco model=\"driveid_" + o.joint + "\">\n";
  out += Provenance(o, "  <!--", " -->");
  out += fmt::format("  <!-- {} -->\n  <!-- {} -->\n  <!-- {} -->\n", CommentText(WithStd(file, "inertia", v.p.inertia, unit)),
                     CommentText(WithStd(file, "viscous", v.p.viscous, rate)),
                     CommentText(WithStd(file, "coulomb", v.p.coulomb, force)));
  if (g.mass > 0.0) {
    out += fmt::format("  <!-- gravity Kg = {:.6g} {} at Kg_angle = {:.6g} rad: a point mass carrying {:g} % of the "
                       "inertia -->\n", v.gravity, CommentText(force), v.gravity_angle, 100.0 * kGravityBodyShare);
  }
  for (const std::string& note : NotRepresented(v, true)) out += "  <!-- " + CommentText(note) + " -->\n";
  out += MjcfOptionLines();
  out += "  <worldbody>\n";
  out += fmt::format("    <body name=\"{}_link\">\n", o.joint);
  out += fmt::format("      <joint name=\"{}\" type=\"{}\" axis=\"{}\" armature=\"{}\" damping=\"{}\" frictionloss=\"{}\" "
                     "solreffriction=\"{} 1\"/>\n",
                     o.joint, v.linear ? "slide" : "hinge", v.linear ? "1 0 0" : "0 -1 0", Number(armature),
                     Number(v.damping), Number(v.friction), Number(2.0 * kMjcfTimestep));
  out += fmt::format("      <inertial pos=\"{} 0 {}\" mass=\"{}\" diaginertia=\"{} {} {}\"/>\n", Number(g.x), Number(g.z),
                     Number(body_mass), Number(own), Number(own), Number(own));
  out += "    </body>\n  </worldbody>\n  <actuator>\n";
  out += fmt::format("    <!-- force = ctrl - tau_0 ({}): ctrl is the logged effort in {} -->\n", Number(v.p.offset),
                     CommentText(force));
  out += fmt::format("    <general name=\"{}_motor\" joint=\"{}\" gainprm=\"1\" biastype=\"affine\" biasprm=\"{} 0 0\"/>\n",
                     o.joint, o.joint, Number(v.p.offset == 0.0 ? 0.0 : -v.p.offset));
  out += "  </actuator>\n</mujoco>\n";
  return out;
}

std::string ExportUrdf(const ParameterFile& file, const ExportOptions& o) {
  const AxisView v = ViewAxis(file);
  RequireInertia(v);
  const GravityBody g = MakeGravityBody(v);
  std::string out = "<?xml version=\"1.0\"?>\n";
  out += Provenance(o, "<!--", " -->");
  std::vector<std::string> absent = {"rotor inertia (armature)", "offset"};
  for (const AxisTerm* term : AxisTerms()) {
    if (!term->ExportNote(AxisExportTarget::kSimulator).empty()) absent.push_back(term->name() + " term");
  }
  std::string list;
  for (std::size_t i = 0; i < absent.size(); ++i) {
    list += (i == 0 ? "no " : i + 1 == absent.size() ? " and no " : ", no ") + absent[i];
  }
  out += "<!-- URDF holds damping and friction per joint; it has " + list + ": the link's inertia carries J -->\n";
  for (const std::string& note : NotRepresented(v, false)) out += "<!-- " + CommentText(note) + " -->\n";
  out += fmt::format("<robot name=\"driveid_{}\">\n  <link name=\"base\"/>\n  <link name=\"{}_link\">\n", o.joint, o.joint);
  double mass = 0.0, inertia = 0.0;
  if (v.linear) {
    mass = v.p.inertia;
    inertia = OwnBodyInertia(v.p.inertia);
  } else {
    mass = g.mass > 0.0 ? g.mass : OwnBodyInertia(v.p.inertia);
    inertia = v.p.inertia - g.mass * g.radius * g.radius;  // about the axis through the centre of mass
  }
  out += fmt::format("    <inertial>\n      <origin xyz=\"{} 0 {}\"/>\n      <mass value=\"{}\"/>\n", Number(g.x),
                     Number(g.z), Number(mass));
  out += fmt::format("      <inertia ixx=\"{0}\" ixy=\"0\" ixz=\"0\" iyy=\"{0}\" iyz=\"0\" izz=\"{0}\"/>\n    </inertial>\n",
                     Number(inertia));
  out += "  </link>\n";
  out += fmt::format("  <joint name=\"{}\" type=\"{}\">\n    <parent link=\"base\"/>\n    <child link=\"{}_link\"/>\n",
                     o.joint, v.linear ? "prismatic" : "continuous", o.joint);
  out += fmt::format("    <axis xyz=\"{}\"/>\n", v.linear ? "1 0 0" : "0 -1 0");
  out += fmt::format("    <dynamics damping=\"{}\" friction=\"{}\"/>\n", Number(v.damping), Number(v.friction));
  if (v.linear) {
    out += "    <!-- URDF requires limits on a prismatic joint: not identified, set them from the machine -->\n";
    out += "    <limit lower=\"-1\" upper=\"1\" effort=\"0\" velocity=\"0\"/>\n";
  }
  out += "  </joint>\n</robot>\n";
  return out;
}

WpilibAxis WpilibOf(const ParameterFile& file) {
  const AxisView v = ViewAxis(file);
  return {RequireFeedforward(file), v.linear, TermNotes(v, AxisExportTarget::kWpilib), &file.feedback};
}

// The axis feed-forward section, or the C-drive's compensation law (31).
const Feedforward& GainsOf(const ParameterFile& file) {
  if (file.feedforward.law == kCDriveCompensationLaw && !file.feedforward.gains.empty()) return file.feedforward;
  return RequireFeedforward(file);
}

std::string ExportCHeader(const ParameterFile& file, const ExportOptions& o) {
  const Feedforward& ff = GainsOf(file);
  const std::string upper = UpperCase(o.joint);
  const char* law =
      ff.law == kCDriveCompensationLaw
          ? "/* eq. (31), per motor I with the other J: tau_I = beta w_I + delta RL{sgn DZ(w_I)} + gamma_half (w_I - w_J)"
            " + eta RL{sgn DZ(w_I - w_J)}; DZ the dead zone dead_zone, RL the rate limit rate_limit "
            "(docs/models.md#c-drive) */\n"
          : "/* u = Ks sgn(v) + Kv v + Ka a + Kg cos(q - Kg_angle) + offset (docs/models.md#feed-forward) */\n";
  std::string out = CHeaderOpen(o, upper, law);
  for (const FeedforwardGain& g : ff.gains) {
    out += fmt::format("DRIVEID_CONSTANT {}_{} = {};  /* {} */\n", upper, g.key, Number(g.value), CommentText(g.unit));
    out += fmt::format("DRIVEID_CONSTANT {}_{}_STD = {:.6g};\n", upper, g.key, g.standard_error);
  }
  out += FeedbackCHeaderLines(file.feedback, upper);
  out += CHeaderClose(upper);
  return out;
}

std::string ExportJson(const ParameterFile& file, const ExportOptions& o) {
  const Feedforward& ff = GainsOf(file);
  Json doc = Json::object();
  doc["source"] = o.source;
  doc["joint"] = o.joint;
  doc["law"] = ff.law;
  doc["effort_unit"] = ff.effort_unit;
  doc["position_unit"] = ff.position_unit;
  Json gains = Json::object();
  for (const FeedforwardGain& g : ff.gains) gains[g.key] = {{"value", g.value}, {"std", g.standard_error}, {"unit", g.unit}};
  doc["gains"] = gains;
  if (!file.feedback.empty()) doc["feedback"] = FeedbackJson(file.feedback);
  return DumpJson(doc);
}

}  // namespace

ExportTarget ParseExportTarget(const std::string& name) {
  ExportTarget target{};
  if (FindExportTarget(name, &target)) return target;
  throw InputError(fmt::format("export target '{}': one of {}", CommentText(name), fmt::join(ExportTargetNames(), ", ")));
}

std::string ExportParameters(const ParameterFile& file, ExportTarget target, const ExportOptions& options) {
  RequireValid(options);
  if (file.feedforward.law == kCDriveCompensationLaw && target != ExportTarget::kCHeader &&
      target != ExportTarget::kJson) {
    throw InputError(fmt::format("the C-drive's compensation law (31) couples the two motors through their rate "
                                 "difference: MJCF and URDF joints hold friction per joint and WPILib has no such class; "
                                 "export it to {} (docs/export.md#c-drive)",
                                 ListExportTargets({ExportTarget::kCHeader, ExportTarget::kJson})));
  }
  if (file.Find<SerialRobotSection>() != nullptr) return ExportSerialRobot(file, target, options);
  const JointSection* joint = file.Find<JointSection>();
  if (joint != nullptr && file.Find<AxisSection>() == nullptr) return ExportJoint(*joint, file, target, options);
  switch (target) {
    case ExportTarget::kMjcf: return ExportMjcf(file, options);
    case ExportTarget::kUrdf: return ExportUrdf(file, options);
    case ExportTarget::kWpilibJava: return ExportWpilibJava(WpilibOf(file), options);
    case ExportTarget::kWpilibCpp: return ExportWpilibCpp(WpilibOf(file), options);
    case ExportTarget::kCHeader: return ExportCHeader(file, options);
    case ExportTarget::kJson: return ExportJson(file, options);
  }
  return {};
}

}  // namespace driveid
