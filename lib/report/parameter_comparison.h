// Parameter files compared with a base (docs/guide.md#fleets-and-drift),
// rendered: the comparison's records and its text, JSON and plot. The
// arithmetic and the drift gate are workflow/drift_comparison.h.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/fit_result.h"
#include "report/json.h"
#include "report/plot.h"

namespace driveid {

struct DriftGate {
  std::optional<double> max_percent;  ///< |relative change| above this [%] drifts
  std::optional<double> max_z;        ///< |z| above this drifts
  std::vector<std::string> parameters;  ///< compared (empty: all of the base's)
};

struct ParameterChange {
  std::string name;
  double base = 0.0, base_std = 0.0, value = 0.0, value_std = 0.0;
  double relative_change = 0.0;  ///< (value - base) / |base|; NaN when base is 0
  double z = 0.0;                ///< NaN when both stds are 0
  bool drift = false;
};

struct FileComparison {
  std::string file;
  bool drift = false;                     ///< any parameter drifted
  std::vector<ParameterChange> parameters;  ///< in the base's order
  std::vector<std::string> missing;       ///< compared parameters the file has no estimate of
  /// Why the gate (when one is set) cannot judge a parameter of this file:
  /// no estimate in the file, a base of 0 under a percent gate, no std on
  /// either side under a z gate. A gate that cannot judge fails.
  std::vector<std::string> undecided;
};

/// One block per file: each parameter's base, value, change and z, drift
/// marked; a closing line with how many files drifted.
std::string FormatComparisons(const std::string& base_file, const std::vector<FileComparison>& files,
                              const DriftGate& gate);
/// {"base", "gate", "files": [{"file", "drift", "missing", "parameters":
/// {NAME: {"base", "base_std", "value", "std", "relative_change", "z",
/// "drift"}}}], "drifted"}; NaN as null.
Json ComparisonsJson(const std::string& base_file, const std::vector<FileComparison>& files, const DriftGate& gate);
/// A panel per parameter: the relative change [%] of each file in the order
/// given (the x axis: file 1, 2, ...), with +-2 combined std as a band and
/// the gate's percentage as lines.
std::vector<PlotPanel> ComparisonPanels(const std::vector<FileComparison>& files, const DriftGate& gate);

}  // namespace driveid
