// The MAT reader proper: libmatio (v5 and v7.3), HDF5 and zlib below it,
// run as its own process, driveid-mat-reader (lib/logs/formats/mat_reader_main.cc),
// started by the MAT source (lib/logs/formats/mat_source.cc). So the tools map those
// libraries (and what HDF5 pulls in: curl, Kerberos, LDAP, ...) only when a
// MAT file is read, and a corrupt file that makes them crash, hang or
// allocate without bound ends that process, not the tool.
#pragma once

#include <string>

#include "logs/formats/mat_reply.h"

namespace driveid {

/// Reads the MAT file `file` (a copy of `bytes`, which came from `path`):
/// the structural checks first (logs/formats/mat_structure_check.h,
/// logs/formats/hdf5_storage_check.h; the tool has run logs/formats/hdf5_length_check.h), then
/// every numeric vector and matrix, struct fields by dotted path; other
/// classes are notes. Throws InputError naming `path`.
MatContents ReadMatFile(const std::string& path, const std::string& file, const std::string& bytes);

/// The reader process's reply (logs/formats/mat_reply.h) for the MAT file `file`,
/// named `path` in messages: its contents or the error that ended reading.
std::string MatReaderReply(const std::string& path, const std::string& file);

/// `file` may be /proc/self/fd/N, an unnamed copy (the tools pass one, so
/// that nothing named is left behind); a v7.3 (HDF5) file is then read from
/// a named copy in a private folder of the temporary directory for the
/// length of the read, since HDF5 cannot open the unnamed one.

/// Async-signal-safe: removes that named copy, if one exists now. For the
/// reader process's signal handlers.
void RemoveMatReaderCopyNow() noexcept;

/// Writes `reply` to the file descriptor `fd`; false if it could not.
bool WriteMatReaderReply(int fd, const std::string& reply);

}  // namespace driveid
