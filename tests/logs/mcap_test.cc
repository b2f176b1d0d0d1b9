// The MCAP reader (logs/formats/mcap.h) on files written here from the
// published record layout (mcap.dev/spec: an opcode byte, a little-endian
// uint64 length, the content; strings and byte arrays length-prefixed),
// independently of the reader: an uncompressed chunk whose records hold a
// schema and a channel is read, and the same chunk with its uncompressed
// CRC-32 off by one bit is refused naming the chunk's offset — without the
// check its bytes (a changed value, not a changed length) would pass.
#include <cstdint>
#include <string>

#include <catch2/catch.hpp>
#include <zlib.h>

#include "core/errors.h"
#include "logs/formats/mcap.h"
#include "system/byte_source.h"

using namespace driveid;

namespace {

template <class T>
std::string Little(T value) {
  std::string out;
  for (std::size_t i = 0; i < sizeof(T); ++i) out += static_cast<char>((static_cast<std::uint64_t>(value) >> (8 * i)) & 0xFF);
  return out;
}
std::string Text(const std::string& s) { return Little<std::uint32_t>(static_cast<std::uint32_t>(s.size())) + s; }
std::string Record(unsigned char opcode, const std::string& content) {
  return std::string(1, static_cast<char>(opcode)) + Little<std::uint64_t>(content.size()) + content;
}

const std::string kMagic("\x89MCAP0\r\n", 8);

// A file of one uncompressed chunk holding a JointState schema and a
// channel on it; `crc_flip` is XORed into the chunk's CRC-32.
std::string McapFile(std::uint32_t crc_flip, std::size_t* chunk_offset) {
  const std::string records =
      Record(0x03, Little<std::uint16_t>(1) + Text("sensor_msgs/msg/JointState") + Text("ros2msg") + Text("")) +
      Record(0x04, Little<std::uint16_t>(7) + Little<std::uint16_t>(1) + Text("/joint_states") + Text("cdr") +
                       Little<std::uint32_t>(0));
  const auto crc = static_cast<std::uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(records.data()), static_cast<uInt>(records.size())));
  std::string file = kMagic + Record(0x01, Text("ros2") + Text("driveid mcap_test"));
  *chunk_offset = file.size();
  file += Record(0x06, Little<std::uint64_t>(0) + Little<std::uint64_t>(0) + Little<std::uint64_t>(records.size()) +
                           Little<std::uint32_t>(crc ^ crc_flip) + Text("") + Little<std::uint64_t>(records.size()) +
                           records);
  file += Record(0x0F, Little<std::uint32_t>(0));
  file += Record(0x02, Little<std::uint64_t>(0) + Little<std::uint64_t>(0) + Little<std::uint32_t>(0));
  return file + kMagic;
}

}  // namespace

TEST_CASE("MCAP: a chunk is read through its records, and refused when its CRC-32 does not match") {
  std::size_t offset = 0;
  const auto none = [](const std::string&) -> JointStateRows* { return nullptr; };
  SECTION("the CRC as written: the channel in the chunk is the bag's topic") {
    const std::string file = McapFile(0, &offset);  // the source views it
    const auto bytes = MemoryBytes("good.mcap", file);
    const auto topics = ReadMcapBag(*bytes, none);
    REQUIRE(topics.size() == 1);
    CHECK(topics[0].name == "/joint_states");
    CHECK(topics[0].type == "sensor_msgs/msg/JointState");
    CHECK(McapComplete(*bytes));
  }
  SECTION("one bit of the CRC changed: refused, naming the chunk") {
    const std::string file = McapFile(1, &offset);
    const auto bytes = MemoryBytes("bad_crc.mcap", file);
    CHECK_THROWS_WITH(ReadMcapBag(*bytes, none),
                      Catch::Contains("bad_crc.mcap: MCAP chunk at offset " + std::to_string(offset)) &&
                          Catch::Contains("CRC-32 mismatch"));
  }
}
