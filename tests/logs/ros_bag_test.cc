// The JointState CDR decoder (logs/formats/ros_bag.h) against messages built here by
// the test's own CDR writer (from the CDR alignment rules): every field
// read back; a message cut at every byte refused as InputError (never a
// crash or an allocation of what a length claims); a sequence claiming
// 2^32 - 1 elements refused before anything is allocated.
#include "logs/formats/ros_bag.h"
#include "logs/formats/ros1_bag.h"
#include "logs/formats/ros_source.h"

#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/errors.h"

using namespace driveid;

namespace {

class Writer {
 public:
  Writer() : bytes_("\x00\x01\x00\x00", 4) {}
  void Align(std::size_t n) {
    while ((bytes_.size() - 4) % n != 0) bytes_ += '\0';
  }
  void U32(std::uint32_t v) {
    Align(4);
    bytes_.append(reinterpret_cast<const char*>(&v), 4);
  }
  void String(const std::string& s) {
    U32(static_cast<std::uint32_t>(s.size() + 1));
    bytes_ += s;
    bytes_ += '\0';
  }
  void Doubles(const std::vector<double>& values) {
    U32(static_cast<std::uint32_t>(values.size()));
    if (!values.empty()) Align(8);
    for (double v : values) bytes_.append(reinterpret_cast<const char*>(&v), 8);
  }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

std::string Message() {
  Writer w;
  w.U32(12);           // sec
  w.U32(345'000'000);  // nanosec
  w.String("base_link");
  w.U32(2);
  w.String("shoulder");
  w.String("elbow");
  w.Doubles({0.5, -1.25});
  w.Doubles({});
  w.Doubles({3.0, 4.5});
  return w.bytes();
}

}  // namespace

// A bag's stamps in seconds are the nearest doubles, as the CSV of their
// decimal text reads (issue 71: (double)ns / 1e9 rounded twice, one stamp in
// four an ulp off). Against strtod of the text printed here by snprintf.
TEST_CASE("bag stamps: the nearest double to ns x 1e-9, as the decimal text reads") {
  std::uint64_t state = 42;
  int differ_naive = 0;
  for (int i = 0; i < 2000; ++i) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    const std::int64_t ns = 1700000000000000000LL + static_cast<std::int64_t>(state >> 20);
    char text[40];
    std::snprintf(text, sizeof text, "%lld.%09lld", static_cast<long long>(ns / 1000000000), static_cast<long long>(ns % 1000000000));
    const double expected = std::strtod(text, nullptr);
    CHECK(driveid::NearestSeconds(ns) == expected);
    differ_naive += static_cast<double>(ns) / 1e9 != expected;
  }
  CHECK(differ_naive > 0);  // the case the test is about occurs
  CHECK(driveid::NearestSeconds(1500000000) == 1.5);
  CHECK(driveid::NearestSeconds(-2500000000) == -2.5);
  CHECK(driveid::NearestSeconds(-1700000000123456789LL) == -std::strtod("1700000000.123456789", nullptr));
}

TEST_CASE("a JointState in CDR: stamp, names and arrays read back, an empty array kept empty") {
  const std::string m = Message();
  const JointStateMessage read = DecodeJointStateCdr("m", m.data(), m.size());
  CHECK(read.stamp_ns == 12'345'000'000LL);
  CHECK(read.name == std::vector<std::string>{"shoulder", "elbow"});
  CHECK(read.position == std::vector<double>{0.5, -1.25});
  CHECK(read.velocity.empty());
  CHECK(read.effort == std::vector<double>{3.0, 4.5});
}

TEST_CASE("a JointState cut at every byte is refused by name, never read past its end") {
  const std::string m = Message();
  for (std::size_t cut = 0; cut < m.size(); ++cut) {
    INFO("cut at " << cut);
    const std::string prefix = m.substr(0, cut);
    // The cut message is copied to a buffer of exactly its size: a read
    // past it is a sanitizer error.
    std::vector<char> exact(prefix.begin(), prefix.end());
    CHECK_THROWS_AS(DecodeJointStateCdr("cut", exact.data(), exact.size()), InputError);
  }
}

TEST_CASE("lengths that claim more than the message holds are refused before allocating") {
  Writer w;
  w.U32(1);
  w.U32(0);
  w.String("");
  w.U32(0xffffffffU);  // name[] claims 4 G strings
  CHECK_THROWS_WITH(DecodeJointStateCdr("m", w.bytes().data(), w.bytes().size()),
                    Catch::Contains("m: name[] claims 4294967295 elements, 0 bytes remain"));
  Writer d;
  d.U32(1);
  d.U32(0);
  d.String("");
  d.U32(0);
  d.U32(100000000U);  // position[] claims 10^8 doubles
  CHECK_THROWS_WITH(DecodeJointStateCdr("m", d.bytes().data(), d.bytes().size()),
                    Catch::Contains("position[] claims 100000000 elements"));
  Writer n;
  n.U32(1);
  n.U32(1'500'000'000U);  // nanosec beyond a second
  n.String("");
  CHECK_THROWS_WITH(DecodeJointStateCdr("m", n.bytes().data(), n.bytes().size()), Catch::Contains("nanosec = 1500000000"));
}

TEST_CASE("a ROS 1 JointState: read back; cut at every byte refused; huge counts refused before allocating") {
  std::string m;
  const auto u32 = [&](std::uint32_t v) { m.append(reinterpret_cast<const char*>(&v), 4); };
  const auto str = [&](const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size()));
    m += s;
  };
  const auto doubles = [&](const std::vector<double>& v) {
    u32(static_cast<std::uint32_t>(v.size()));
    for (double d : v) m.append(reinterpret_cast<const char*>(&d), 8);
  };
  u32(7);  // seq
  u32(3);
  u32(500);
  str("base");
  u32(1);
  str("elbow");
  doubles({1.5});
  doubles({});
  doubles({-2.0});
  const JointStateMessage read = DecodeJointStateRos1("r", m.data(), m.size());
  CHECK(read.stamp_ns == 3'000'000'500LL);
  CHECK(read.name == std::vector<std::string>{"elbow"});
  CHECK(read.position == std::vector<double>{1.5});
  CHECK(read.velocity.empty());
  CHECK(read.effort == std::vector<double>{-2.0});
  for (std::size_t cut = 0; cut < m.size(); ++cut) {
    std::vector<char> exact(m.begin(), m.begin() + static_cast<std::ptrdiff_t>(cut));
    CHECK_THROWS_AS(DecodeJointStateRos1("cut", exact.data(), exact.size()), InputError);
  }
  std::string huge = m.substr(0, 16);  // seq, stamp, frame "" -> then a claim
  huge.replace(12, 4, std::string("\0\0\0\0", 4));
  const std::uint32_t claim = 0xffffffffU;
  huge.append(reinterpret_cast<const char*>(&claim), 4);
  CHECK_THROWS_WITH(DecodeJointStateRos1("h", huge.data(), huge.size()), Catch::Contains("h: name[] claims 4294967295 elements"));
}
