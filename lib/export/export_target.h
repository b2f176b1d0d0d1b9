// The export targets (docs/export.md) and the names the options and
// messages spell them with: one table, which parsing, help texts, the
// command line's choices and advice in messages read.
#pragma once

#include <string>
#include <vector>

namespace driveid {

enum class ExportTarget { kMjcf, kUrdf, kWpilibJava, kWpilibCpp, kCHeader, kJson };

/// The target's name: mjcf, urdf, wpilib-java, wpilib-cpp, c-header, json.
const char* ExportTargetName(ExportTarget target);

/// Every target's name, in table order.
std::vector<std::string> ExportTargetNames();
/// The names of `targets`, in their order.
std::vector<std::string> ExportTargetNames(const std::vector<ExportTarget>& targets);

/// "a, b or c" of every target's name.
std::string ListExportTargets();
/// "a, b or c" of the names of `targets`.
std::string ListExportTargets(const std::vector<ExportTarget>& targets);

/// The target a name spells, if one does (parameter_export.h
/// ParseExportTarget refuses the others).
bool FindExportTarget(const std::string& name, ExportTarget* target);

}  // namespace driveid
