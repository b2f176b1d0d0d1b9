#include "export/export_target.h"

#include <array>
#include <utility>

namespace driveid {

namespace {

constexpr std::array<std::pair<ExportTarget, const char*>, 6> kExportTargets{{
    {ExportTarget::kMjcf, "mjcf"},
    {ExportTarget::kUrdf, "urdf"},
    {ExportTarget::kWpilibJava, "wpilib-java"},
    {ExportTarget::kWpilibCpp, "wpilib-cpp"},
    {ExportTarget::kCHeader, "c-header"},
    {ExportTarget::kJson, "json"},
}};

}  // namespace

const char* ExportTargetName(ExportTarget target) {
  for (const auto& [t, name] : kExportTargets) {
    if (t == target) return name;
  }
  return "";
}

std::vector<std::string> ExportTargetNames() {
  std::vector<std::string> names;
  for (const auto& entry : kExportTargets) names.emplace_back(entry.second);
  return names;
}

std::vector<std::string> ExportTargetNames(const std::vector<ExportTarget>& targets) {
  std::vector<std::string> names;
  for (const ExportTarget t : targets) names.emplace_back(ExportTargetName(t));
  return names;
}

namespace {

// "a, b or c".
std::string ListNames(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += i + 1 == names.size() ? " or " : ", ";
    out += names[i];
  }
  return out;
}

}  // namespace

std::string ListExportTargets() { return ListNames(ExportTargetNames()); }

std::string ListExportTargets(const std::vector<ExportTarget>& targets) { return ListNames(ExportTargetNames(targets)); }

bool FindExportTarget(const std::string& name, ExportTarget* target) {
  for (const auto& [t, spelled] : kExportTargets) {
    if (name == spelled) {
      *target = t;
      return true;
    }
  }
  return false;
}

}  // namespace driveid
