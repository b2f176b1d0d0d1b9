// An axis parameter by its key (models/axis.h), member or slot alike: the
// tests name a registered term's parameters as the parameter file does.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>

#include "models/axis.h"

namespace driveid::testing {

inline const AxisRow& AxisRowOf(const std::string& key) {
  const AxisRow* row = FindParameter(AxisParameterTable(), key);
  if (row == nullptr) throw std::logic_error("no axis parameter " + key);
  return *row;
}
inline double& AxisValue(AxisParameters& p, const std::string& key) { return ModelValue(AxisRowOf(key), p); }
inline double AxisValue(const AxisParameters& p, const std::string& key) { return ModelValue(AxisRowOf(key), p); }
inline std::optional<double>& AxisValue(AxisSection& s, const std::string& key) { return SectionValue(AxisRowOf(key), s); }

}  // namespace driveid::testing
