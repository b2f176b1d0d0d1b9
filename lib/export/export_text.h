// What the export targets share (export/parameter_export.h,
// export/joint_export.h): comment-safe text, exact numbers, a value with its
// std from the fit section, the provenance lines, and gravity as a point
// mass for MJCF and URDF.
#pragma once

#include <optional>
#include <string>

#include "params/parameter_file.h"

namespace driveid {

struct ExportOptions {
  std::string joint = "axis";  ///< joint / identifier name: [A-Za-z_][A-Za-z0-9_]*, at most 64 characters
  std::string source;          ///< the parameter file's path, for provenance comments
  std::string command;         ///< the command line, for provenance comments
  std::string urdf;            ///< a serial robot's URDF (default: the path its serial_robot section names)
  /// The joint name's bound (‹joint›; see core/option_check.h).
  bool IsValid(std::string* error) const;
};

}  // namespace driveid

namespace driveid::export_text {

constexpr double kGravity = 9.81;           // m/s^2, MuJoCo's default |g|
constexpr double kGravityBodyShare = 0.01;  // of J carried by the gravity point mass (MJCF, URDF)
constexpr double kMjcfTimestep = 0.001;     // s, the MJCF's <option timestep>

/// Text from a file or the command line inside an XML, C or Java comment:
/// printable ASCII only, no backslash (Java decodes \\u escapes in comments,
/// C splices a line after one), and neither "--" nor "*/" can close the
/// comment, nor a trailing "-" an XML comment; "/*" is broken as "/ *"
/// (gcc's -Wcomment).
std::string CommentText(const std::string& text);
/// `text` for a C, C++ or Java comment: printable ASCII ('?' for others and
/// for a backslash), "*/" broken as "* /" and "/*" as "/ *", "--" kept (a command line stays
/// one that can be pasted back), at most 300 characters.
std::string CodeCommentText(const std::string& text);

/// `text` inside a double-quoted XML attribute: &, <, >, " escaped.
std::string XmlAttribute(const std::string& text);

/// All 17 significant digits.
std::string Number(double value);

/// "name = value +- std unit", or "(not fitted)" when the fit section has no std for it.
std::string WithStd(const ParameterFile& file, const std::string& name, double value, const std::string& unit);

/// Two comment lines: the source file and the command.
std::string Provenance(const ExportOptions& o, const std::string& open, const std::string& close);

/// The file's axis feed-forward section; InputError when it has none.
const Feedforward& RequireFeedforward(const ParameterFile& file);

/// The gain `key` of `ff`, or null.
const FeedforwardGain* Gain(const Feedforward& ff, const std::string& key);

/// `name` in upper case (a C macro prefix).
std::string UpperCase(const std::string& name);

/// A C header's start: provenance, `description` (a comment line), the
/// include guard DRIVEID_<upper>_H and DRIVEID_CONSTANT (static const double
/// in C, inline constexpr double in C++17). CHeaderClose ends the guard.
std::string CHeaderOpen(const ExportOptions& o, const std::string& upper, const std::string& description);
std::string CHeaderClose(const std::string& upper);

/// A simulator body's own inertia [kg m^2] (or mass) under an axis of
/// inertia J: 1e-9 J, but at least kMinBodyInertia — MuJoCo refuses a
/// moving body lighter than mjMINVAL (1e-15), which 1e-9 J falls under for a
/// small motor's 1e-7 kg m^2. Inertias below kMinExportInertia cannot be
/// carried next to such a body (RequireExportInertia: InputError naming `key`).
constexpr double kMinBodyInertia = 1e-12;
constexpr double kMinExportInertia = 1e-9;
double OwnBodyInertia(double inertia);
void RequireExportInertia(const std::string& key, double inertia);

/// The MJCF's solver lines: the time step and why the friction time constant.
std::string MjcfOptionLines();

/// Gravity as a point mass m at distance r from the axis at angle -Kg_angle
/// in the x-z plane, the joint turning about -y: the holding torque is
/// m g r cos(q - Kg_angle) = Kg cos(q - Kg_angle) with Kg = hypot(g_c, g_s),
/// Kg_angle = atan2(g_s, g_c), and m r^2 is kGravityBodyShare of `inertia`.
struct GravityBody {
  double mass = 0.0, radius = 0.0, x = 0.0, z = 0.0;
};
GravityBody MakeGravityBody(double inertia, double gravity_cos, double gravity_sin);

}  // namespace driveid::export_text
