// One check for option values at API boundaries (Ceres-style message):
// "--rate = -5: violated constraint: rate > 0 Hz". Exit code 2 in the tools.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "core/errors.h"

namespace driveid {

/// The message of a violated option constraint, as RequireOption's.
inline std::string ViolatedConstraint(const char* option, double value, const char* constraint) {
  return fmt::format("{} = {}: violated constraint: {}", option, value, constraint);
}

/// Throws OptionError naming the option, its value and the constraint unless `ok`.
inline void RequireOption(bool ok, const char* option, double value, const char* constraint) {
  if (!ok) throw OptionError(ViolatedConstraint(option, value, constraint));
}

/// Options structs validate themselves in one place each, as Ceres's
/// Solver::Options::IsValid: `bool IsValid(std::string* error) const` names
/// the field (‹field›, apps/ prints the flag) and the constraint; this
/// throws OptionError with that message.
template <typename Options>
void RequireValid(const Options& options) {
  std::string error;
  if (!options.IsValid(&error)) throw OptionError(error);
}

/// Most samples a simulated log may have (its memory is bounded, ~100 B per sample).
inline constexpr double kMaxSimulatedSamples = 1e7;

/// Checks the sample count of a simulated log: at least `minimum` (what the
/// fit of such a log accepts) and at most kMaxSimulatedSamples. `cause` names
/// the options that set the count with their values ("--duration 2 at --rate
/// 1000"); throws OptionError.
inline void RequireSampleCount(double samples, std::size_t minimum, const std::string& cause) {
  if (!(samples >= static_cast<double>(minimum))) {
    throw OptionError(fmt::format("{} gives {:.3g} samples: the fit of such a log needs at least {}", cause, samples,
                                  minimum));
  }
  if (!(samples <= kMaxSimulatedSamples)) {
    throw OptionError(fmt::format("{} gives {:.3g} samples: at most {:.0e} (lower one of them)", cause, samples,
                                  kMaxSimulatedSamples));
  }
}

}  // namespace driveid
