// One check for option values at API boundaries (Ceres-style message):
// "--rate = -5: violated constraint: rate > 0 Hz". Exit code 2 in the tools.
#pragma once

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

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

/// The body of an IsValid, one line per declared bound, the first violated
/// one reported (as RequireOption's message):
///   return OptionCheck(error)
///       .Require(decimation >= 1, "‹decimation›", decimation, ">= 1")
///       .Nested(fit);
/// Finite(x) and Positive(x) spell the common bounds without a NaN slipping through.
class OptionCheck {
 public:
  explicit OptionCheck(std::string* error) : error_(error) {}
  OptionCheck& Require(bool ok, const char* option, double value, const char* constraint) {
    if (valid_ && !ok) Fail(ViolatedConstraint(option, value, constraint));
    return *this;
  }
  /// A bound on a value that is not a number (a name, a choice): `message` says it.
  OptionCheck& Require(bool ok, const std::string& message) {
    if (valid_ && !ok) Fail(message);
    return *this;
  }
  /// Options held inside these: their own IsValid.
  template <typename Options>
  OptionCheck& Nested(const Options& nested) {
    if (valid_ && !nested.IsValid(error_)) valid_ = false;
    return *this;
  }
  operator bool() const { return valid_; }  // NOLINT(google-explicit-constructor): IsValid returns it

 private:
  void Fail(std::string message) {
    *error_ = std::move(message);
    valid_ = false;
  }
  std::string* error_;
  bool valid_ = true;
};

inline bool Finite(double x) { return std::isfinite(x); }
inline bool Positive(double x) { return std::isfinite(x) && x > 0.0; }
inline bool NotNegative(double x) { return std::isfinite(x) && x >= 0.0; }

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
