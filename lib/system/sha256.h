// SHA-256 (FIPS 180-4) for the provenance of fitted parameter files.
#pragma once

#include <string>

namespace driveid {

/// Lower-case hexadecimal SHA-256 digest of `bytes`.
std::string Sha256Hex(const std::string& bytes);

class ByteSource;
/// The same of a source's whole content, read piece by piece.
std::string Sha256Hex(ByteSource& bytes);

}  // namespace driveid
