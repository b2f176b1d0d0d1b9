// One check for option values at API boundaries (Ceres-style message):
// "--rate = -5: violated constraint: rate > 0 Hz". Exit code 2 in the tools.
#pragma once

#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "core/errors.h"

namespace driveid {

/// Throws OptionError naming the option, its value and the constraint unless `ok`.
inline void RequireOption(bool ok, const char* option, double value, const char* constraint) {
  if (!ok) throw OptionError(fmt::format("{} = {}: violated constraint: {}", option, value, constraint));
}

}  // namespace driveid
