// Lists of names (parameter keys, column names, joints): the one helper
// every fit and workflow asks of them.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

namespace driveid {

/// Whether `name` is one of `names`.
inline bool Contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace driveid
