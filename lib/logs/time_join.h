// Joining a second file by time (docs/formats.md#joining-by-time): its
// columns interpolated linearly onto the log's time base, after mapping its
// clock onto the log's by a given shift or by cross-correlating a channel
// both files record (signal/clock_alignment.h). Rows of the log outside the
// joined file's span are dropped, with a note.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "logs/table_source.h"

namespace driveid {

struct LogInputOptions;

/// How a joined file meets the log: row by row (`time` empty), or by time.
struct JoinTiming {
  std::string time;              ///< the joined file's time column [s], a column expression
  std::optional<double> shift;   ///< [s] log time = joined time + shift
  std::string align;             ///< "A=B": channel A of the log and B of the joined file, cross-correlated
};

/// The log's source `log` with `joined`'s columns (positions count on),
/// joined by time as `timing` says. The log's time is its time column (as
/// `options` map it) or the ‹rate› base. Throws OptionError for bad
/// expressions or combinations, InputError naming file and line for a time
/// column that does not increase or spans that do not overlap,
/// IdentificationError when the channels do not align.
std::unique_ptr<TableSource> JoinSourcesByTime(std::unique_ptr<TableSource> log, std::unique_ptr<TableSource> joined,
                                               const JoinTiming& timing, const LogInputOptions& options);

}  // namespace driveid
