#include "export/export_text.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"

namespace driveid {

bool ExportOptions::IsValid(std::string* error) const {
  bool valid = !joint.empty() && joint.size() <= 64 &&
               (std::isalpha(static_cast<unsigned char>(joint[0])) || joint[0] == '_');
  for (char c : joint) valid = valid && (std::isalnum(static_cast<unsigned char>(c)) || c == '_');
  return OptionCheck(error).Require(
      valid, fmt::format("‹joint›: joint name '{}': letters, digits and _ only, starting with a letter or _, at most "
                         "64 (it becomes an XML name and a Java/C identifier)", export_text::CommentText(joint)));
}

}  // namespace driveid

namespace driveid::export_text {

std::string CommentText(const std::string& text) {
  std::string out;
  for (char c : text) {
    const bool printable = c >= 0x20 && c < 0x7f;
    // A backslash could start an escape javac decodes even in comments
    // (\u002a/ closes one) or splice a // comment's line in C.
    char kept = printable && c != '\\' ? c : '?';
    // Two dashes would end an XML comment, star-slash a C one, and
    // slash-star inside a C comment is what gcc's -Wcomment warns of.
    if (!out.empty() && ((kept == '-' && out.back() == '-') || (kept == '/' && out.back() == '*') ||
                         (kept == '*' && out.back() == '/'))) {
      out += ' ';
    }
    out += kept;
  }
  if (out.size() > 300) out = out.substr(0, 297) + "...";
  if (!out.empty() && out.back() == '-') out += ' ';  // before an XML comment's "-->"
  return out;
}

std::string Number(double value) { return fmt::format("{:.17g}", value); }

double OwnBodyInertia(double inertia) { return std::max(1e-9 * inertia, kMinBodyInertia); }

void RequireExportInertia(const std::string& key, double inertia) {
  if (!(inertia > 0.0)) {
    throw InputError(fmt::format("{} = {:g}: a simulator model needs an inertia > 0 (fit it, or give it)", key, inertia));
  }
  if (inertia < kMinExportInertia) {
    throw InputError(fmt::format("{} = {:g}: below {:g}, too small to carry beside the {:g} body a simulator needs "
                                 "(check its unit: kg m^2, link side)",
                                 key, inertia, kMinExportInertia, kMinBodyInertia));
  }
}

std::string WithStd(const ParameterFile& file, const std::string& name, double value, const std::string& unit) {
  for (const ParameterEstimate& e : file.fit_estimates) {
    if (e.name == name) return fmt::format("{} = {:.6g} +- {:.3g} {}", name, value, e.standard_error, unit);
  }
  return fmt::format("{} = {:.6g} {} (not fitted)", name, value, unit);
}

std::string XmlAttribute(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string CodeCommentText(const std::string& text) {
  std::string out;
  for (char c : text) {
    const bool printable = c >= 0x20 && c < 0x7f;
    const char kept = printable && c != '\\' ? c : '?';
    if (!out.empty() && ((kept == '/' && out.back() == '*') || (kept == '*' && out.back() == '/'))) out += ' ';
    out += kept;
  }
  if (out.size() > 300) out = out.substr(0, 297) + "...";
  return out;
}

std::string Provenance(const ExportOptions& o, const std::string& open, const std::string& close) {
  // XML comments may not hold "--"; C, C++ and Java comments may, so their
  // command line stays as typed and can be pasted back.
  const bool xml = open.find("<!--") != std::string::npos;
  const auto text = [&](const std::string& t) { return xml ? CommentText(t) : CodeCommentText(t); };
  return fmt::format("{} driveid export of {} (docs/export.md){}\n{} made by: {}{}\n", open, text(o.source), close, open,
                     text(o.command), close);
}

const Feedforward& RequireFeedforward(const ParameterFile& file) {
  if (file.feedforward.gains.empty() || file.feedforward.law != kAxisFeedforwardLaw) {
    throw InputError("no axis 'feedforward' section (an axis fit writes it)");
  }
  return file.feedforward;
}

const FeedforwardGain* Gain(const Feedforward& ff, const std::string& key) {
  for (const FeedforwardGain& g : ff.gains) {
    if (g.key == key) return &g;
  }
  return nullptr;
}

std::string UpperCase(const std::string& name) {
  std::string upper;
  for (char c : name) upper += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return upper;
}

std::string CHeaderOpen(const ExportOptions& o, const std::string& upper, const std::string& description) {
  std::string out = Provenance(o, "/*", " */") + description;
  out += fmt::format("#ifndef DRIVEID_{0}_H\n#define DRIVEID_{0}_H\n\n", upper);
  out += "#ifndef DRIVEID_CONSTANT\n#ifdef __cplusplus\n#define DRIVEID_CONSTANT inline constexpr double\n#else\n"
         "#define DRIVEID_CONSTANT static const double\n#endif\n#endif\n\n";
  return out;
}

std::string CHeaderClose(const std::string& upper) { return fmt::format("\n#endif /* DRIVEID_{}_H */\n", upper); }

std::string MjcfOptionLines() {
  std::string out = "  <!-- frictionloss is MuJoCo's soft dry friction, not a sticking Coulomb law: docs/export.md -->\n";
  out += fmt::format("  <option timestep=\"{}\"/>  <!-- the log's sample time or less -->\n", Number(kMjcfTimestep));
  out += fmt::format("  <!-- solreffriction {}: the stiffest friction loss MuJoCo allows at this timestep (twice it); "
                     "a joint at rest creeps in proportion to it (MuJoCo's default 0.02 s creeps ten times "
                     "faster) -->\n", Number(2.0 * kMjcfTimestep));
  return out;
}

GravityBody MakeGravityBody(double inertia, double gravity_cos, double gravity_sin) {
  GravityBody b;
  const double gravity = std::hypot(gravity_cos, gravity_sin);
  if (gravity == 0.0) return b;
  const double angle = std::atan2(gravity_sin, gravity_cos);
  b.radius = kGravityBodyShare * inertia * kGravity / gravity;
  b.mass = gravity / (kGravity * b.radius);
  b.x = b.radius * std::cos(-angle);
  b.z = b.radius * std::sin(-angle);
  return b;
}

}  // namespace driveid::export_text
