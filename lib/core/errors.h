// Error types thrown across the library boundary. Each maps to one exit code
// of the command-line tools (docs/formats.md#exit-codes); anything else that
// escapes (std::logic_error, a plain std::invalid_argument) is a bug: exit 1.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace driveid {

/// Invalid input: unreadable or malformed CSV/YAML, missing column, NaN/Inf,
/// non-increasing time, unknown key, out-of-range value. Exit code 3.
/// The message already names the file (and line and column where known).
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

/// An output that cannot be written: unwritable path, a plot renderer
/// (gnuplot) missing or failing, a full disk. Exit code 3, naming the file.
class OutputError : public std::runtime_error {
 public:
  explicit OutputError(const std::string& message) : std::runtime_error(message) {}
};

/// An option value the library refuses (names the option, its value and the
/// violated constraint). Exit code 2, like a command-line usage error.
class OptionError : public std::runtime_error {
 public:
  explicit OptionError(const std::string& message) : std::runtime_error(message) {}
};

/// Identification failed: parameters not identifiable from the data, solver
/// not converged, integrator failure. Exit code 4.
class IdentificationError : public std::runtime_error {
 public:
  explicit IdentificationError(const std::string& message, std::vector<std::string> parameters = {})
      : std::runtime_error(message), parameters_(std::move(parameters)) {}
  /// The parameters the data do not determine, where the refusal names them.
  const std::vector<std::string>& parameters() const { return parameters_; }

 private:
  std::vector<std::string> parameters_;
};

}  // namespace driveid
