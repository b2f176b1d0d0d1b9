// system/file_reading.h: a whole file read within its limits, or refused
// naming the file (and line, or offset) — a directory, a file over its size,
// a binary byte in a text file, an over-long line (kept for a structured
// file), a FIFO no writer opens — never a hang or an unbounded read.
#include <chrono>
#include <fstream>
#include <string>
#include <string_view>

#include <sys/stat.h>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "support/private_tmpdir.h"
#include "system/file_reading.h"

using namespace driveid;

namespace {

std::string Write(const std::string& dir, const std::string& name, const std::string& bytes) {
  const std::string path = dir + "/" + name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

}  // namespace

TEST_CASE("file reading: whole within the limits, else refused naming the file and where") {
  const driveid::testing::PrivateTmpdir tmp;
  const std::string dir = tmp.path();
  SECTION("a text file is read whole") {
    CHECK(ReadFileToString(Write(dir, "a.csv", "t,q\n0,1\n")) == "t,q\n0,1\n");
  }
  SECTION("a directory and a missing file") {
    CHECK_THROWS_WITH(ReadFileToString(dir), Catch::Contains(dir + ": is a directory, not a file"));
    CHECK_THROWS_AS(ReadFileToString(dir + "/none.csv"), InputError);
  }
  SECTION("over the size limit, before a byte is read; the hint says how to raise it") {
    ReadLimits limits;
    limits.max_bytes = 8;
    limits.max_bytes_hint = "raise it with --max-log-size";
    const std::string path = Write(dir, "big.csv", "t,q\n0,1\n1,2\n");
    CHECK_THROWS_WITH(ReadFileToString(path, limits),
                      Catch::Contains(path + ": larger than 8 bytes (raise it with --max-log-size)"));
  }
  SECTION("a binary byte in a text file: its line and offset") {
    const std::string path = Write(dir, "bin.csv", std::string("t,q\n0,\0", 7));
    CHECK_THROWS_WITH(ReadFileToString(path), Catch::Contains(path + ":2: byte 0x00 at offset 6: not a text file"));
  }
  SECTION("an over-long line: refused in text, kept in a structured file") {
    ReadLimits limits;
    limits.max_line_bytes = 16;
    const std::string line(40, 'x');
    const std::string path = Write(dir, "long.json", "{\"a\": \"" + line + "\"}\n");
    CHECK_THROWS_WITH(ReadFileToString(path, limits), Catch::Contains(path + ":1: line longer than 16 bytes"));
    limits.structured = [](std::string_view head) { return head.substr(0, 1) == "{"; };
    CHECK(ReadFileToString(path, limits).size() == line.size() + 10);
  }
  SECTION("a FIFO without a writer: an error within its wait, not a hang") {
    const std::string path = dir + "/fifo";
    REQUIRE(::mkfifo(path.c_str(), 0600) == 0);
    ReadLimits limits;
    limits.fifo_wait_seconds = 0.2;
    const auto start = std::chrono::steady_clock::now();
    CHECK_THROWS_WITH(ReadFileToString(path, limits), Catch::Contains("a FIFO that no process wrote to within"));
    CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(5));
  }
}
