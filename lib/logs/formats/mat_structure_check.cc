#include "logs/formats/mat_structure_check.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

#include <fmt/format.h>
#include <zlib.h>

#include "core/errors.h"

namespace driveid {
namespace {

constexpr std::size_t kHeaderBytes = 128;
constexpr std::uint32_t kMatrix = 14, kCompressed = 15;

// Little-endian file unless its endian indicator reads "MI".
struct Reader {
  const unsigned char* data;
  std::size_t size;
  bool swap;
  bool Has(std::size_t at, std::size_t n) const { return at <= size && n <= size - at; }
  std::uint32_t U32(std::size_t at) const {
    std::uint32_t v = 0;
    std::memcpy(&v, data + at, 4);
    return swap ? __builtin_bswap32(v) : v;
  }
};

std::size_t Padded(std::size_t n) { return (n + 7) / 8 * 8; }

// The array name inside a miMATRIX element's content, or "" if it cannot be read.
std::string MatrixName(const Reader& r) {
  std::size_t at = 16;  // array flags: tag and 8 bytes
  if (!r.Has(at, 8)) return {};
  std::uint32_t word = r.U32(at);
  at += (word >> 16) != 0 ? 8 : 8 + Padded(r.U32(at + 4));  // dimensions
  if (!r.Has(at, 8)) return {};
  word = r.U32(at);
  std::size_t length = 0, start = 0;
  if ((word >> 16) != 0) {  // small element: up to 4 bytes in the tag
    length = word >> 16;
    start = at + 4;
    if (length > 4) return {};
  } else {
    length = r.U32(at + 4);
    start = at + 8;
  }
  if (length > 256 || !r.Has(start, length)) return {};
  return std::string(reinterpret_cast<const char*>(r.data + start), length);
}

std::string Named(const std::string& name, std::size_t index) {
  return name.empty() ? fmt::format("data element {} (its name unreadable)", index) : fmt::format("variable {}", name);
}

// Inflates a compressed element (nothing kept beyond its first bytes) and
// compares the inflated size with the miMATRIX tag it starts with.
void CheckCompressed(const std::string& path, const unsigned char* data, std::size_t size, bool swap,
                     std::size_t index) {
  z_stream z{};
  if (inflateInit(&z) != Z_OK) throw InputError(fmt::format("{}: cannot start zlib", path));
  std::vector<unsigned char> head;  // the first inflated bytes: tag and name
  std::vector<unsigned char> buffer(1 << 16);
  std::uint64_t total = 0, declared = 0;
  bool have_declared = false, ended = false;
  std::size_t offered = 0;
  int status = Z_OK;
  while (true) {
    if (z.avail_in == 0 && offered < size) {
      const std::size_t n = std::min<std::size_t>(size - offered, 1u << 30);
      z.next_in = const_cast<unsigned char*>(data + offered);
      z.avail_in = static_cast<uInt>(n);
      offered += n;
    }
    z.next_out = buffer.data();
    z.avail_out = static_cast<uInt>(buffer.size());
    status = inflate(&z, Z_NO_FLUSH);
    const std::size_t produced = buffer.size() - z.avail_out;
    if (head.size() < 4096) head.insert(head.end(), buffer.begin(), buffer.begin() + std::min(produced, 4096 - head.size()));
    total += produced;
    if (!have_declared && head.size() >= 8) {
      Reader r{head.data(), head.size(), swap};
      declared = 8 + static_cast<std::uint64_t>(r.U32(4));
      have_declared = true;
    }
    if (status == Z_STREAM_END) {
      ended = true;
      break;
    }
    if (have_declared && total > declared + 8) break;  // more than it claims: no need to go on
    if (status != Z_OK && !(status == Z_BUF_ERROR && produced > 0)) break;
  }
  inflateEnd(&z);
  const std::string name = head.size() >= 8 ? MatrixName(Reader{head.data() + 8, head.size() - 8, swap}) : "";
  if (!ended && !(have_declared && total > declared + 8)) {
    throw InputError(fmt::format("{}: {}: its compressed data end early ({} of its {} bytes inflated, zlib: {}): the "
                                 "file is cut short or corrupt",
                                 path, Named(name, index), total, have_declared ? fmt::format("{}", declared) : "?",
                                 z.msg != nullptr ? z.msg : zError(status)));
  }
  if (have_declared && total != declared) {
    throw InputError(fmt::format("{}: {}: inflates to {} bytes, its header claims {} ({} {}): the file is corrupt",
                                 path, Named(name, index), total, declared,
                                 total < declared ? declared - total : total - declared,
                                 total < declared ? "missing" : "too many"));
  }
}

}  // namespace

void CheckMatV5Elements(const std::string& path, const std::string& bytes) {
  if (bytes.size() < kHeaderBytes) return;  // matio says what is wrong
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const bool little = data[126] == 'I' && data[127] == 'M', big = data[126] == 'M' && data[127] == 'I';
  if (!little && !big) return;
  Reader r{data, bytes.size(), big};
  const std::uint16_t version = static_cast<std::uint16_t>(big ? (data[124] << 8) | data[125] : (data[125] << 8) | data[124]);
  if (version != 0x0100) return;  // v7.3: HDF5
  std::size_t at = kHeaderBytes, index = 0;
  while (at < bytes.size()) {
    ++index;
    if (!r.Has(at, 8)) {
      throw InputError(fmt::format("{}: the file ends inside the tag of data element {} ({} of 8 bytes; cut short?)",
                                   path, index, bytes.size() - at));
    }
    const std::uint32_t type = r.U32(at), count = r.U32(at + 4);
    const std::size_t content = at + 8;
    std::string name;
    if (type == kMatrix) name = MatrixName(Reader{data + content, bytes.size() - content, big});
    if (!r.Has(content, count)) {
      throw InputError(fmt::format("{}: {} is cut short: the file ends {} bytes before its end (it needs {} bytes "
                                   "from byte {})",
                                   path, Named(name, index), count - (bytes.size() - content), count, content));
    }
    if (type == kCompressed) CheckCompressed(path, data + content, count, big, index);
    at = content + (type == kCompressed ? count : Padded(count));
  }
}

}  // namespace driveid
