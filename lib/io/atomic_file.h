// Atomic file output: write to a temporary file in the same directory, flush
// it to disk, then rename over the target. A reader never sees a partial
// file, and on any failure the previous file (if any) is left untouched.
#pragma once

#include <string>

namespace driveid {

/// Writes `contents` to `path` atomically; throws InputError naming the path
/// when the directory is not writable or the disk is full.
void WriteFileAtomically(const std::string& path, const std::string& contents);

}  // namespace driveid
