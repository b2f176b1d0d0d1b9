// MAT files, v5 and v7.3 (docs/formats.md#logs): a table source whose
// columns are the variables' vectors, matrix rows and columns, read in a
// child process (logs/formats/mat_source.cc).
#pragma once

#include <memory>
#include <string>

#include "logs/table_source.h"

namespace driveid {

/// The MAT reader alone (v5 and v7.3 through libmatio).
std::unique_ptr<TableSource> OpenMatSource(const std::string& path, const std::string& text);
/// Reads the MAT file `file` (named `path` in messages) and writes the
/// reader's reply (logs/formats/mat_reply.h) to `fd`; false if it could not.
using MatReaderInChild = bool (*)(int fd, const std::string& path, const std::string& file);
/// Where a MAT file is read: by default the reader process
/// driveid-mat-reader (logs/formats/mat_reader.h), exec'd in the forked child. A
/// program that links the reader itself (the fuzzers: an exec per input
/// would slow them tenfold) may have the forked child call `reader`
/// instead, with the same limits. Set once, before any MAT file is read.
void ReadMatFilesInForkedChild(MatReaderInChild reader);

}  // namespace driveid
