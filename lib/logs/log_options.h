// The options every log is read with (`--col`, the formats' own, `--rate`,
// `--from/--to`, the time column), apart from the reading itself
// (logs/log_input.h) so that the time join can take them too.
#pragma once

#include <map>
#include <optional>
#include <string>

#include "logs/table_source.h"

namespace driveid {

/// A log column whose largest magnitude exceeds this (or is below the
/// smallest, other than all zeros) is refused: a fit could not square it.
inline constexpr double kLargestLogMagnitude = 1e150;
inline constexpr double kSmallestLogMagnitude = 1e-150;

struct LogInputOptions {
  /// Logical column name -> expression (`--col NAME=EXPR`).
  std::map<std::string, std::string> columns;
  CsvFormat csv;
  LogSelection selection;
  double rate = 0.0;  ///< --rate [Hz]: samples at this rate from t = 0 (0: the time column)
  std::optional<double> from, to;  ///< --from, --to [s]: crop in the log's time
  std::string time_column = "t";   ///< strictly increasing
  /// ‹unit›: the unit of the position column q ("" = the log's own, as its
  /// reader declares it: SysId's `units`, a WPILog entry's metadata). A log
  /// that declares a unit and a ‹col› q that rescales the position need it:
  /// the label would not follow the numbers.
  std::string position_unit;
  /// Every bound on these fields (‹field› names the option); see core/option_check.h.
  bool IsValid(std::string* error) const;
};

}  // namespace driveid
