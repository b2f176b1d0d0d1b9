// The WPILog record reader (logs/formats/wpilog.h) against logs built here by a
// writer of the test's own (from the published format): entries and their
// counts, the values of each numeric type, negative timestamps left out,
// records of no started entry counted, metadata changed; a log cut at every
// byte is read exactly when the cut falls between records, else refused
// with the offset; sizes claimed beyond the file are refused.
#include "logs/formats/wpilog.h"

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/errors.h"

using namespace driveid;

namespace {

std::string Little(std::uint64_t value, int bytes) {
  std::string out;
  for (int i = 0; i < bytes; ++i) out += static_cast<char>((value >> (8 * i)) & 0xff);
  return out;
}

int Width(std::uint64_t value, int most) {
  int n = 1;
  while (n < most && value >= (std::uint64_t{1} << (8 * n))) ++n;
  return n;
}

// A record with the shortest fields; a negative time takes 8 bytes.
std::string Record(std::uint32_t entry, std::int64_t time, const std::string& payload) {
  std::uint64_t raw = 0;
  std::memcpy(&raw, &time, 8);
  const int e = Width(entry, 4), s = Width(payload.size(), 4), t = time < 0 ? 8 : Width(raw, 8);
  std::string out(1, static_cast<char>((e - 1) | ((s - 1) << 2) | ((t - 1) << 4)));
  return out + Little(entry, e) + Little(payload.size(), s) + Little(raw, t) + payload;
}

std::string Text(const std::string& s) { return Little(s.size(), 4) + s; }

std::string Start(std::uint32_t id, const std::string& name, const std::string& type, const std::string& meta) {
  return Record(0, 0, std::string(1, '\0') + Little(id, 4) + Text(name) + Text(type) + Text(meta));
}

std::string Double(double v) {
  std::string out(8, '\0');
  std::memcpy(out.data(), &v, 8);
  return out;
}

struct Built {
  std::string bytes;
  std::vector<std::size_t> boundaries;  // where a record ends (and the header)
};

Built Sample() {
  Built b;
  b.bytes = "WPILOG" + Little(0x0100, 2) + Text("extra");
  b.boundaries.push_back(b.bytes.size());
  const auto add = [&](const std::string& r) {
    b.bytes += r;
    b.boundaries.push_back(b.bytes.size());
  };
  add(Start(1, "voltage", "double", "Volt"));
  add(Start(70000, "count", "int64", ""));
  add(Start(3, "state", "string", ""));
  add(Start(4, "ratio", "float", ""));
  add(Start(5, "on", "boolean", ""));
  add(Record(1, 1000, Double(1.5)));
  add(Record(1, 3'000'000'000LL, Double(-2.25)));  // a 5-byte timestamp
  add(Record(70000, 2000, Little(static_cast<std::uint64_t>(-7), 8)));
  add(Record(3, 2500, "quasistatic-forward"));
  float ratio = 0.5F;
  std::string f(4, '\0');
  std::memcpy(f.data(), &ratio, 4);
  add(Record(4, 2600, f));
  add(Record(5, 2700, std::string(1, '\1')));
  add(Record(1, -3, Double(9.0)));  // retained: a negative time
  add(Record(99, 4000, Double(1.0)));  // no such entry
  add(Record(0, 5000, std::string(1, '\2') + Little(1, 4) + Text("Volts")));
  add(Record(0, 6000, std::string(1, '\1') + Little(3, 4)));
  add(Record(3, 7000, "none"));  // after its Finish
  return b;
}

}  // namespace

TEST_CASE("entries, values of each type, negative times and records of no entry") {
  const Built b = Sample();
  std::vector<std::pair<std::string, double>> numbers;
  std::vector<std::string> strings;
  const WpilogIndex index = ReadWpilog("s.wpilog", b.bytes, [&](const WpilogRecord& r) {
    double v = 0.0;
    if (WpilogNumber(r.entry->type, r.payload, v)) numbers.emplace_back(r.entry->name, v);
    else strings.emplace_back(r.payload);
  });
  CHECK(index.version == 0x0100);
  CHECK(index.extra_header == "extra");
  REQUIRE(index.entries.size() == 5);
  CHECK(index.entries[0].name == "voltage");
  CHECK(index.entries[0].metadata == "Volts");  // changed by Set metadata
  CHECK(index.entries[0].records == 2);
  CHECK(index.entries[0].negative_records == 1);
  CHECK(index.entries[0].first_us == 1000);
  CHECK(index.entries[0].last_us == 3'000'000'000LL);
  CHECK(index.entries[1].id == 70000);
  CHECK(index.orphan_records == 2);  // entry 99, and "state" after its Finish
  CHECK(numbers == std::vector<std::pair<std::string, double>>{
                       {"voltage", 1.5}, {"voltage", -2.25}, {"count", -7.0}, {"ratio", 0.5}, {"on", 1.0}});
  CHECK(strings == std::vector<std::string>{"quasistatic-forward"});
  double v = 0.0;
  CHECK_FALSE(WpilogNumber("double", "1234567", v));  // 7 bytes
  CHECK_FALSE(WpilogNumber("string", "12345678", v));
}

TEST_CASE("a log cut at every byte: read when the cut falls between records, else refused with its offset") {
  const Built b = Sample();
  for (std::size_t cut = 0; cut < b.bytes.size(); ++cut) {
    const std::string prefix = b.bytes.substr(0, cut);
    const bool boundary = std::find(b.boundaries.begin(), b.boundaries.end(), cut) != b.boundaries.end();
    INFO("cut at " << cut);
    if (boundary) {
      CHECK_NOTHROW(ReadWpilog("c.wpilog", prefix));
    } else {
      try {
        ReadWpilog("c.wpilog", prefix);
        FAIL("read");
      } catch (const InputError& e) {
        const std::string m = e.what();
        CHECK((m.find("c.wpilog: record at offset") == 0 || m.find("c.wpilog: not a WPILib DataLog") == 0 ||
               m.find("c.wpilog: the extra header claims") == 0));
      }
    }
  }
}

TEST_CASE("claims beyond the file or the record, and unknown control records, are refused by offset") {
  const std::string header = "WPILOG" + Little(0x0100, 2) + Text("");
  // A payload of 4 GiB - 1 claimed by a 4-byte size.
  const std::string huge = header + std::string(1, static_cast<char>(3 << 2)) + Little(1, 1) + Little(0xffffffff, 4) +
                           Little(0, 1) + "abc";
  CHECK_THROWS_WITH(ReadWpilog("h.wpilog", huge),
                    "h.wpilog: record at offset 12 claims 4294967295 bytes of payload, 3 remain in the file");
  // A Start whose name claims more than the record holds.
  const std::string name = header + Record(0, 0, std::string(1, '\0') + Little(1, 4) + Little(1000, 4) + "ab");
  CHECK_THROWS_WITH(ReadWpilog("n.wpilog", name), Catch::Contains("n.wpilog: control record at offset 12: the entry name "
                                                                  "claims 1000 bytes, 2 remain in the record"));
  CHECK_THROWS_WITH(ReadWpilog("k.wpilog", header + Record(0, 0, std::string(1, '\7'))),
                    "k.wpilog: control record at offset 12: unknown control type 7");
  CHECK_THROWS_WITH(ReadWpilog("v.wpilog", "WPILOG" + Little(0x0200, 2) + Text("")),
                    "v.wpilog: WPILog version 2.0: this reader knows version 1.x");
}
