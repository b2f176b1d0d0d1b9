// The numbers a parameter file holds (docs/formats.md): read and written
// by every section alike.
#pragma once

namespace driveid {

/// Numbers in parameter files are 0 or within these magnitudes (docs/formats.md).
inline constexpr double kSmallestParameterMagnitude = 1e-100;
inline constexpr double kLargestParameterMagnitude = 1e100;

}  // namespace driveid
