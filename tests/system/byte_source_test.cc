// The piece-by-piece reader of large logs (system/byte_source.h): a file read
// through its read-ahead window gives the bytes a whole read gives, for
// views inside a window, across a window's end, longer than a window and
// at the file's end; a range past the end is refused naming the file;
// the streamed SHA-256 equals the whole one; a FIFO is no streamable file.
#include "system/byte_source.h"

#include <cstdio>
#include <fstream>
#include <random>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "system/sha256.h"

using namespace driveid;

namespace {

std::string TempPath(const char* name) { return std::string(P_tmpdir) + "/driveid_" + std::to_string(::getpid()) + name; }

}  // namespace

TEST_CASE("a file viewed piece by piece gives the bytes it holds") {
  std::mt19937 rng(7);
  std::string bytes(9 << 20, '\0');  // over two read-ahead windows
  for (char& c : bytes) c = static_cast<char>(rng());
  const std::string path = TempPath("_bytes.bin");
  std::ofstream(path, std::ios::binary) << bytes;
  {
    auto file = OpenFileBytes(path);
    REQUIRE(file);
    auto memory = MemoryBytes("m", bytes);
    CHECK(file->size() == bytes.size());
    CHECK(file->memory() == nullptr);
    CHECK(memory->memory() == &bytes);
    const std::uint64_t window = 4 << 20;
    for (const auto& [offset, length] : std::vector<std::pair<std::uint64_t, std::uint64_t>>{
             {0, 9}, {100, 1000}, {window - 3, 9}, {window - 3, 9}, {5, window}, {window + 17, 3 << 20},
             {bytes.size() - 1, 1}, {bytes.size(), 0}, {0, bytes.size()}, {12345, 0}}) {
      INFO("offset " << offset << " length " << length);
      CHECK(file->View(offset, length) == std::string_view(bytes).substr(offset, length));
      CHECK(memory->View(offset, length) == std::string_view(bytes).substr(offset, length));
    }
    CHECK_THROWS_WITH(file->View(bytes.size() - 2, 3), Catch::StartsWith(path + ": 3 bytes at offset"));
    CHECK_THROWS_AS(file->View(std::uint64_t{1} << 62, std::uint64_t{1} << 62), InputError);
    CHECK_THROWS_AS(memory->View(bytes.size() + 1, 0), InputError);
    CHECK(Sha256Hex(*file) == Sha256Hex(bytes));
    CHECK_NOTHROW(file->CheckUnchanged());
    std::ofstream(path, std::ios::binary | std::ios::app) << "more";
    CHECK_THROWS_WITH(file->CheckUnchanged(), Catch::Contains("changed while it was read"));
  }
  std::remove(path.c_str());
}

TEST_CASE("only a regular file is streamed; a missing one is refused by name") {
  const std::string fifo = TempPath("_fifo");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  CHECK(OpenFileBytes(fifo) == nullptr);
  std::remove(fifo.c_str());
  CHECK_THROWS_WITH(OpenFileBytes(TempPath("_missing")), Catch::Contains("cannot open file for reading"));
}
