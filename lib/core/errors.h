// Error types thrown across the library boundary. Each maps to one exit code
// of the command-line tools (SPEC section 7).
#pragma once

#include <stdexcept>
#include <string>

namespace driveid {

/// Invalid input: unreadable or malformed CSV/YAML, missing column, NaN/Inf,
/// non-increasing time, unknown key, out-of-range value. Exit code 3.
/// The message already names the file (and line and column where known).
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

/// Identification failed: parameters not identifiable from the data, solver
/// not converged, integrator failure. Exit code 4.
class IdentificationError : public std::runtime_error {
 public:
  explicit IdentificationError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace driveid
