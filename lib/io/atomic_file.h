// Atomic file output: write to a temporary file in the same directory, flush
// it to disk, then rename over the target. A reader never sees a partial
// file, and on any failure the previous file (if any) is left untouched.
// Only regular files are ever replaced: a device, FIFO or socket is written
// in place (as root, renaming over /dev/null would replace the device), a
// directory or a read-only file is refused, and a symbolic link is written
// through to its target. A new file gets 0666 less the umask; an existing
// file keeps its permissions.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace driveid {

/// Writes `contents` to `path` as above; throws OutputError (exit 3) naming
/// the path when it cannot (directory not writable, disk full, read-only).
void WriteFileAtomically(const std::string& path, const std::string& contents);

/// Writes several files (path, contents) all or nothing: each is first
/// written to a temporary file beside it, and only when every one is written
/// are they renamed into place (devices and FIFOs written last, in place).
/// On a failure before the renames no file is changed.
void WriteFilesAtomically(const std::vector<std::pair<std::string, std::string>>& files);

}  // namespace driveid
