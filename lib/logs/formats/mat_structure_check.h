// Structural checks of a MAT file before matio reads it. v5: matio reads a
// data element that the file ends inside of as zeros, and a compressed
// element that inflates to less than its header claims the same way; the
// top-level elements are walked (tag: type, byte count) and every
// compressed one inflated once (nothing kept) to compare its size. The v7.3
// (HDF5) length check is logs/formats/hdf5_length_check.h.
#pragma once

#include <string>

namespace driveid {

/// Throws InputError naming `path`, the variable (where its name can be read)
/// and the missing bytes when the file ends inside an element, or a
/// compressed element's stream ends early or inflates to another size than
/// its header claims. Files that are not MAT v5 (v7.3 is HDF5, which checks
/// itself) pass unchecked.
void CheckMatV5Elements(const std::string& path, const std::string& bytes);

}  // namespace driveid
