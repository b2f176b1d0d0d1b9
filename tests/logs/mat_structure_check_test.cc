// The structural checks run before matio and HDF5 read a MAT file
// (logs/formats/mat_structure_check.h, logs/formats/hdf5_length_check.h), on files written by
// matio: a v5 file cut at every length is refused exactly when the cut
// falls inside a data element (the boundaries found here by walking the
// tags), a compressed element claiming another size is refused, and a v7.3
// file cut anywhere after its superblock is refused with the bytes missing.
#include <cstdint>
#include <cstring>
#include <set>
#include <string>

#include <catch2/catch.hpp>
#include <zlib.h>
#include <fmt/format.h>

#include "core/errors.h"
#include "logs/formats/hdf5_length_check.h"
#include "logs/formats/mat_structure_check.h"
#include "support/mat_fixture.h"

namespace driveid {
namespace {

std::uint32_t Word(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, bytes.data() + at, 4);
  return v;
}

// The ends of the top-level data elements of a little-endian v5 file
// (128-byte header; an element is an 8-byte tag and its data padded to 8,
// a compressed one (type 15) unpadded).
std::set<std::size_t> ElementEnds(const std::string& bytes) {
  std::set<std::size_t> ends{128};
  std::size_t at = 128;
  while (at + 8 <= bytes.size()) {
    const std::uint32_t type = Word(bytes, at), size = Word(bytes, at + 4);
    const std::size_t data = type == 15 ? size : (size + 7) / 8 * 8;
    at += 8 + data;
    ends.insert(at);
  }
  REQUIRE(at == bytes.size());
  return ends;
}

TEST_CASE("MAT v5 cut at every length: refused naming the file exactly when the cut is inside an element") {
  const std::string bytes = testing::WriteMat(MAT_FT_MAT5);
  REQUIRE(bytes.substr(126, 2) == "IM");  // little endian
  const std::set<std::size_t> ends = ElementEnds(bytes);
  REQUIRE(ends.size() >= 5);
  int refused = 0, wrong = 0;
  for (std::size_t length = 128; length <= bytes.size(); ++length) {
    bool threw = false;
    try {
      CheckMatV5Elements("log.mat", bytes.substr(0, length));
    } catch (const InputError& e) {
      threw = std::string(e.what()).rfind("log.mat: ", 0) == 0;
      refused += 1;
    }
    const bool boundary = ends.count(length) > 0;
    if (threw == boundary) {
      ++wrong;
      UNSCOPED_INFO("length " << length << (boundary ? " (a boundary) refused" : " passed"));
    }
  }
  CHECK(wrong == 0);
  CHECK(refused > 100);
}

TEST_CASE("MAT v5: a compressed element whose header claims more bytes than it inflates to is refused") {
  std::string bytes = testing::WriteMat(MAT_FT_MAT5);
  // The compressed element ('data'): inflate it here, claim 8 bytes more in
  // its inner tag, deflate it again and put it back with its new length.
  std::size_t at = 128;
  while (Word(bytes, at) != 15) at += 8 + (Word(bytes, at + 4) + 7) / 8 * 8;
  const std::uint32_t stored = Word(bytes, at + 4);
  std::string inner(4096, '\0');
  uLongf inner_size = inner.size();
  REQUIRE(uncompress(reinterpret_cast<Bytef*>(inner.data()), &inner_size,
                     reinterpret_cast<const Bytef*>(bytes.data() + at + 8), stored) == Z_OK);
  inner.resize(inner_size);
  const std::uint32_t claimed = Word(inner, 4) + 8;
  std::memcpy(inner.data() + 4, &claimed, 4);
  std::string deflated(compressBound(inner.size()), '\0');
  uLongf deflated_size = deflated.size();
  REQUIRE(compress(reinterpret_cast<Bytef*>(deflated.data()), &deflated_size,
                   reinterpret_cast<const Bytef*>(inner.data()), inner.size()) == Z_OK);
  deflated.resize(deflated_size);
  const auto length = static_cast<std::uint32_t>(deflated.size());
  bytes.replace(at + 8, stored, deflated);
  std::memcpy(bytes.data() + at + 4, &length, 4);
  CHECK_THROWS_WITH(CheckMatV5Elements("log.mat", bytes),
                    Catch::Contains("log.mat: variable data: inflates to") && Catch::Contains("the file is corrupt"));
}

TEST_CASE("MAT v7.3 (HDF5) cut after its superblock: refused with the bytes missing; whole, or not HDF5, passes") {
  const std::string bytes = testing::WriteMat(MAT_FT_MAT73);
  CHECK_NOTHROW(CheckHdf5Length("log.mat", bytes));
  CHECK_NOTHROW(CheckHdf5Length("log.csv", "t,q\n0,1\n"));
  int wrong = 0;
  for (std::size_t length = 1024; length < bytes.size(); length += 7) {
    const std::string message = fmt::format("log.mat: the file is cut short: HDF5 wrote {} bytes, the file has {} ({} missing)",
                                            bytes.size(), length, bytes.size() - length);
    try {
      CheckHdf5Length("log.mat", bytes.substr(0, length));
      ++wrong;
    } catch (const InputError& e) {
      wrong += e.what() == message ? 0 : 1;
    }
  }
  CHECK(wrong == 0);
}

}  // namespace
}  // namespace driveid
