// A MAT v7.3 file is HDF5, and HDF5 can make a dataset read bytes from
// elsewhere: external raw storage (a list of other files), external links
// (an object in another HDF5 file) and virtual datasets (mapped from other
// files). A log may only supply its own bytes, so these are refused before
// matio reads a variable (docs/formats.md#logs).
#pragma once

#include <string>

namespace driveid {

/// Walks every link of the HDF5 file `file` (the reader's temporary copy)
/// and throws InputError naming `path` and the object when a link is
/// external or a dataset has external storage or a virtual layout. A file
/// HDF5 cannot open passes (matio says what is wrong with it).
void CheckHdf5Storage(const std::string& path, const std::string& file);

}  // namespace driveid
