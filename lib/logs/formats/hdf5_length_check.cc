#include "logs/formats/hdf5_length_check.h"

#include <cstdint>
#include <cstring>

#include <fmt/format.h>

#include "core/errors.h"

namespace driveid {
namespace {

bool Has(std::size_t size, std::size_t at, std::size_t n) { return at <= size && n <= size - at; }

}  // namespace

void CheckHdf5Length(const std::string& path, const std::string& bytes) {
  static const char kSignature[] = "\x89HDF\r\n\x1a\n";
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  for (std::size_t at = 0; at + 8 <= bytes.size(); at = at == 0 ? 512 : 2 * at) {
    if (std::memcmp(data + at, kSignature, 8) != 0) continue;
    if (!Has(bytes.size(), at, 13)) break;
    const unsigned version = data[at + 8];
    // Addresses follow the fixed fields: version 0 and 1 (sizes at +13,
    // addresses from +24 or +28), 2 and 3 (sizes at +9, addresses from +12).
    const std::size_t offsets = version >= 2 ? data[at + 9] : data[at + 13];
    const std::size_t first = version >= 2 ? 12 : version == 0 ? 24 : 28;
    const std::size_t eof_at = at + first + 2 * offsets;
    if (offsets < 2 || offsets > 8 || !Has(bytes.size(), eof_at, offsets)) break;
    std::uint64_t eof = 0;
    for (std::size_t k = 0; k < offsets; ++k) eof |= static_cast<std::uint64_t>(data[eof_at + k]) << (8 * k);
    if (eof != ~std::uint64_t{0} >> (64 - 8 * offsets) && eof > bytes.size()) {
      throw InputError(fmt::format("{}: the file is cut short: HDF5 wrote {} bytes, the file has {} ({} missing)", path,
                                   eof, bytes.size(), eof - bytes.size()));
    }
    break;
  }
}

}  // namespace driveid
