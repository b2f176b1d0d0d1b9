// logs/log_format.h: the format registry. Every format registered once, in
// DRIVEID_LOG_FORMATS' order, CSV last and taking any file; each format told
// from its own first bytes (written here from the formats' published
// magics, not from the readers); an option of another format refused with
// its owner's words, by name; a structured file read without the line limit.
#include <algorithm>
#include <set>
#include <string>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "logs/log_format.h"

using namespace driveid;

namespace {

std::string Sniffed(const std::string& head) { return SniffLogFormat(head).name; }

}  // namespace

TEST_CASE("log formats: each registered once, told from its first bytes, CSV last") {
  std::set<std::string> names;
  for (const LogFormat& f : LogFormats()) {
    INFO(f.name);
    CHECK(names.insert(f.name).second);
    CHECK(!f.source.empty());
    CHECK(!f.kind.empty());
    for (const auto& declared : f.declared) {
      CHECK(std::find(f.options.begin(), f.options.end(), declared.name) != f.options.end());
    }
  }
  REQUIRE(!LogFormats().empty());
  CHECK(LogFormats().back().name == "csv");
  CHECK(Sniffed("t,q,tau\n0,0,0\n") == "csv");
  CHECK(Sniffed("") == "csv");
  CHECK(Sniffed("\xEF\xBB\xBF  \n{\"test\": \"Simple\"}") == "sysid-json");
  CHECK(Sniffed(std::string("WPILOG\x00\x01", 8)) == "wpilog");
  CHECK(Sniffed(std::string("SQLite format 3\0", 16)) == "rosbag2-sqlite3");
  CHECK(Sniffed(std::string("\x89MCAP0\r\n", 8)) == "rosbag2-mcap");
  CHECK(Sniffed("#ROSBAG V2.0\n") == "ros1");
  std::string mat(128, ' ');
  mat.replace(0, 19, "MATLAB 5.0 MAT-file");
  CHECK(Sniffed(mat) == "mat");
  CHECK(Sniffed(mat.substr(0, 100)) == "csv");  // a MAT header is 128 bytes
  CHECK(Sniffed(std::string("\x89HDF\r\n\x1a\n", 8)) == "mat");  // refused as a MAT file without its header
  CHECK(IsStructuredLog("{\"a\": 1}"));
  CHECK(IsStructuredLog(std::string("\x89MCAP0\r\n", 8)));
  CHECK(!IsStructuredLog("t,q\n"));
  CHECK(FindLogFormatOfSource("rosbag") != nullptr);
  CHECK(FindLogFormatOfSource("rosbag")->streamed);
  CHECK(FindLogFormatOfSource("none") == nullptr);
}

TEST_CASE("log formats: an option of another format is refused by name, with its owner's words") {
  const std::string csv = "t,q,tau\n0,0,0\n1,1,1\n";
  LogSelection selection;
  selection.wpilog.motor = "left";
  CHECK_THROWS_WITH(OpenTableSources("a.csv", csv, {}, selection),
                    "‹motor›: a.csv is no WPILog; ‹motor› chooses in a SysIdRoutine's .wpilog");
  selection = {};
  selection.bag.time = "receive";
  CHECK_THROWS_WITH(OpenTableSources("a.csv", csv, {}, selection),
                    "‹time›: a.csv is no ROS bag; ‹time› chooses in a bag's JointState topic");
  selection = {};
  selection.sysid.side = "left";
  CHECK_THROWS_WITH(OpenTableSources("a.csv", csv, {}, selection),
                    "‹side› left: a.csv is a CSV file; ‹side› applies to SysId Drivetrain files");
  CHECK_THROWS_AS(OpenTableSources("x.wpilog", std::string("WPILOG\x00\x01", 8), {}, selection),
                  OptionError);
  selection = {};
  const auto sources = OpenTableSources("a.csv", csv, {}, selection);
  REQUIRE(sources.size() == 1);
  CHECK(sources.front()->format() == "csv");
}
