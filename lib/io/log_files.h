// Reading a command's log files with their provenance (docs/formats.md#logs):
// each file read once within its size limit, hashed, refused when its
// contents were given already, its logs read (a SysId file gives several)
// and each one's record kept for the parameter file's `fit` section.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/fit_result.h"
#include "io/csv_log.h"
#include "io/log_input.h"
#include "io/time_join.h"

namespace driveid {

/// One log file and the file joined to it (join_path empty: none).
struct LogFileRequest {
  std::string path;
  std::string join_path;
  JoinTiming join_timing;
};

/// Reads each file of `files` in order (at most limits.max_bytes; the joined
/// file too), refuses (OptionError) a file whose contents were given already
/// — the same data twice would count twice and shrink every std by sqrt(2) —
/// reads its logs (ReadLogs with `columns` and `options`; `transpose`: one
/// signal per row, io/transpose_table.h), and hands each to `take` after
/// appending its record (file, SHA-256, samples, segment, reader notes and
/// the joined file with its SHA-256) to `records`.
void ReadLogFiles(const std::vector<LogFileRequest>& files, const std::vector<std::string>& columns,
                  const LogInputOptions& options, const ReadLimits& limits, bool transpose,
                  std::vector<DataFileRecord>& records, const std::function<void(CsvLog)>& take);

}  // namespace driveid
