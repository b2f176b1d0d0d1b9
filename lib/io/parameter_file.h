// Parameter files (SPEC section 4): YAML with one section per model, plain
// values a controller can read, and a separate `fit` section with the
// statistics and provenance written by the fitting commands.
//
// Reading is strict: unknown keys, non-numbers, NaN/Inf and out-of-range
// values throw InputError "file:line:column: section.key: what".
#pragma once

#include <optional>
#include <string>

#include "fit/fit_result.h"
#include "models/drivetrain.h"

namespace driveid {

struct ParameterFile {
  std::optional<DriveTrainParameters> drivetrain;
  bool had_fit_section = false;  ///< input carried a previous fit (replaced on output)
};

/// Parses YAML text; `path` is used in messages only.
ParameterFile ParseParameterFile(const std::string& path, const std::string& text);
/// Reads and parses a file.
ParameterFile ReadParameterFile(const std::string& path);

/// Formats a parameter file; with `fit`/`provenance` non-null a `fit`
/// section is added. Output is deterministic and reads back unchanged.
std::string FormatParameterFile(const ParameterFile& file, const FitResult* fit = nullptr,
                                const FitProvenance* provenance = nullptr);

}  // namespace driveid
