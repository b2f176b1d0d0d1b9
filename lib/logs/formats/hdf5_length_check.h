// The length check of a MAT v7.3 (HDF5) file, in the tool before a MAT
// reader process starts: the superblock's end-of-file address says how long
// the file was written; a shorter file is cut short (HDF5 would say so after
// the reader process started; this says it at once, with the bytes missing).
#pragma once

#include <string>

namespace driveid {

/// Throws InputError naming `path` and the missing bytes when an HDF5
/// superblock (at 0, 512, 1024, ... as HDF5 looks for it) records an
/// end-of-file address beyond the file's length. Anything else passes.
void CheckHdf5Length(const std::string& path, const std::string& bytes);

}  // namespace driveid
