// Reading a whole file within limits: an endless or oversized input, a
// directory, binary bytes in a text file, or a FIFO without a writer fail
// fast with InputError naming the file (docs/architecture.md#hostile-input).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace driveid {

/// Limits enforced while a file is read (an endless input fails fast).
struct ReadLimits {
  std::size_t max_bytes = std::size_t{4} << 30;  ///< whole file (default 4 GiB)
  std::size_t max_line_bytes = 1 << 20;         ///< one line; 0 = no limit (binary files)
  /// Drop the line limit when this says the file's first chunk starts a
  /// structured file (logs/log_format.h IsStructuredLog; the whole-file limit still holds).
  bool (*structured)(std::string_view first_chunk) = nullptr;
  std::string max_bytes_hint = "a log may be at most 4 GiB";  ///< how to raise max_bytes, for the message
  double fifo_wait_seconds = 5.0;  ///< a named FIFO's writer must send its first bytes within this
};

/// Reads a whole file into memory; throws InputError naming the file (and
/// the line) when it cannot be read, is a directory or exceeds `limits`
/// (a regular file by its size, before reading), when a line-oriented file
/// holds a control byte (binary data: refused at its first chunk), when a
/// named FIFO gets no writer in time, or when it does not fit in memory.
std::string ReadFileToString(const std::string& path, const ReadLimits& limits = {});

}  // namespace driveid
