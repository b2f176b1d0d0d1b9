// Reading a command's log files with their provenance (docs/formats.md#logs):
// each file read once within its size limit, hashed, refused when its
// contents were given already, its logs read (a SysId file gives several)
// and each one's record kept for the parameter file's `fit` section.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/fit_result.h"
#include "logs/csv_log.h"
#include "logs/log_input.h"
#include "logs/time_join.h"

namespace driveid {

/// A log file as the readers take it: whole in memory, except a ROS bag on
/// a regular file, of which only the first bytes are held — the bag readers
/// stream it from `stream_file` (system/byte_source.h) — with its SHA-256 when
/// asked for (a streamed bag's is read piece by piece too).
struct LogFileBytes {
  std::string text, sha256, stream_file;
};

/// Reads `path` (a rosbag2 folder: its storage file) within `limits`.
LogFileBytes ReadLogFile(const std::string& path, const ReadLimits& limits, bool hash);

/// One log file and the file joined to it (join_path empty: none).
struct LogFileRequest {
  std::string path;
  std::string join_path;
  JoinTiming join_timing;
  /// A path given (the joined file's timing is checked where it is joined).
  bool IsValid(std::string* error) const;
};

/// Reads each file of `files` in order (at most limits.max_bytes; the joined
/// file too), refuses (OptionError) a file whose contents were given already
/// — the same data twice would count twice and shrink every std by sqrt(2) —
/// reads its logs (ReadLogs with `columns` and `options`; `transpose`: one
/// signal per row, logs/transpose_table.h), and hands each to `take` after
/// appending its record (file, SHA-256, samples, segment, reader notes and
/// the joined file with its SHA-256) to `records`.
void ReadLogFiles(const std::vector<LogFileRequest>& files, const std::vector<std::string>& columns,
                  const LogInputOptions& options, const ReadLimits& limits, bool transpose,
                  std::vector<DataFileRecord>& records, const std::function<void(CsvLog)>& take);

}  // namespace driveid
