// The MAT reader's reply (logs/formats/mat_reply.h): what the child serialises the
// parent reads back exactly; every truncation, an oversized claim and the
// child's error come back as InputError naming the file.
#include <string>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "logs/formats/mat_reply.h"

namespace driveid {
namespace {

MatContents Example() {
  MatContents c;
  c.variables.push_back({"rec.pos", 3, 2, {1.0, 2.0, 3.0, -4.5, 1e300, 0.0}});
  c.variables.push_back({"t", 1, 1, {0.25}});
  c.variables.push_back({"empty", 0, 5, {}});
  c.notes = {"skipped 'name': a character array", ""};
  return c;
}

TEST_CASE("a reply reads back exactly") {
  const MatContents in = Example();
  const MatContents out = DeserialiseMatReply("log.mat", SerialiseMatReply(in));
  REQUIRE(out.variables.size() == in.variables.size());
  for (std::size_t i = 0; i < in.variables.size(); ++i) {
    CHECK(out.variables[i].name == in.variables[i].name);
    CHECK(out.variables[i].rows == in.variables[i].rows);
    CHECK(out.variables[i].cols == in.variables[i].cols);
    CHECK(out.variables[i].data == in.variables[i].data);
  }
  CHECK(out.notes == in.notes);
  CHECK(DeserialiseMatReply("x.mat", SerialiseMatReply({})).variables.empty());
}

TEST_CASE("a reply cut anywhere is refused naming the file; the child's error is passed on") {
  const std::string reply = SerialiseMatReply(Example());
  for (std::size_t length = 0; length < reply.size(); ++length) {
    INFO("cut at " << length << " of " << reply.size());
    CHECK_THROWS_WITH(DeserialiseMatReply("log.mat", reply.substr(0, length)), Catch::Contains("log.mat: the MAT reader"));
  }
  CHECK_THROWS_WITH(DeserialiseMatReply("log.mat", SerialiseMatError("log.mat: not a MAT file")),
                    "log.mat: not a MAT file");
}

TEST_CASE("a variable claiming more than kMaxMatElements is refused before any allocation") {
  MatContents c;
  c.variables.push_back({"big", 1, 1, {7.0}});
  std::string reply = SerialiseMatReply(c);
  // Layout: tag, count, name length, name, rows, cols, data, note count.
  const std::size_t rows_at = 1 + 8 + 8 + 3;
  const std::uint64_t huge = std::uint64_t{1} << 40;
  reply.replace(rows_at, 8, std::string(reinterpret_cast<const char*>(&huge), 8));
  CHECK_THROWS_WITH(DeserialiseMatReply("big.mat", reply), "big.mat: variable too large");
}

}  // namespace
}  // namespace driveid
