// Structural checks of a MAT file before matio reads it. v5: matio reads a
// data element that the file ends inside of as zeros, and a compressed
// element that inflates to less than its header claims the same way; the
// top-level elements are walked (tag: type, byte count) and every
// compressed one inflated once (nothing kept) to compare its size. v7.3
// (HDF5): the superblock's end-of-file address says how long the file was
// written; a shorter file is cut short (HDF5 would say so after a reader
// process started; this says it at once, with the bytes missing).
#pragma once

#include <string>

namespace driveid {

/// Throws InputError naming `path`, the variable (where its name can be read)
/// and the missing bytes when the file ends inside an element, or a
/// compressed element's stream ends early or inflates to another size than
/// its header claims. Files that are not MAT v5 (v7.3 is HDF5, which checks
/// itself) pass unchecked.
void CheckMatV5Elements(const std::string& path, const std::string& bytes);

/// Throws InputError naming `path` and the missing bytes when an HDF5
/// superblock (at 0, 512, 1024, ... as HDF5 looks for it) records an
/// end-of-file address beyond the file's length. Anything else passes.
void CheckHdf5Length(const std::string& path, const std::string& bytes);

}  // namespace driveid
