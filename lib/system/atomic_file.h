// Atomic file output: write to a temporary file in the same directory, flush
// it to disk, then rename over the target. A reader never sees a partial
// file, and on any failure the previous file (if any) is left untouched.
// Only regular files are ever replaced: a device, FIFO or socket is written
// in place (as root, renaming over /dev/null would replace the device), a
// directory or a read-only file is refused, and a symbolic link is written
// through to its target. A new file gets 0666 less the umask; an existing
// file keeps its permissions.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace driveid {

/// Writes `contents` to `path` as above; throws OutputError (exit 3) naming
/// the path when it cannot (directory not writable, disk full, read-only).
void WriteFileAtomically(const std::string& path, const std::string& contents);

/// Writes several files (path, contents) as one transaction: each regular
/// file is first written to a temporary file beside it; then devices and
/// FIFOs are written in place (a FIFO without a reader fails here), then
/// `before_commit` runs (the caller's standard output, which can fail too);
/// only when all of that succeeded are the temporary files renamed into
/// place. On any failure before the renames no regular file is changed.
void WriteFilesAtomically(const std::vector<std::pair<std::string, std::string>>& files,
                          const std::function<void()>& before_commit = {});

}  // namespace driveid
