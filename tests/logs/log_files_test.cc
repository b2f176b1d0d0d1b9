// logs/log_files.h: each file read once and hashed, the same contents given
// twice refused by name, a record per log with the joined file's hash, and
// the size limit's hint in the refusal.
#include "logs/log_files.h"

#include <filesystem>
#include <fstream>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "system/sha256.h"

using namespace driveid;

namespace {

std::string Write(const std::filesystem::path& dir, const std::string& name, const std::string& text) {
  const std::filesystem::path path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

}  // namespace

TEST_CASE("log files: records with hashes, joins noted, duplicates refused, limits named") {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "driveid_log_files_test";
  std::filesystem::create_directories(dir);
  const std::string a_text = "t,q\n0,1\n0.1,2\n0.2,3\n";
  const std::string a = Write(dir, "a.csv", a_text);
  const std::string b = Write(dir, "b.csv", "t,q\n0,4\n0.1,5\n");
  const std::string j = Write(dir, "j.csv", "u\n7\n8\n");
  const std::string copy = Write(dir, "copy.csv", a_text);
  LogInputOptions options;
  std::vector<DataFileRecord> records;
  std::vector<CsvLog> logs;
  const auto take = [&](CsvLog csv) { logs.push_back(std::move(csv)); };
  ReadLogFiles({{a, "", {}}, {b, j, {}}}, {"t", "q", "?u"}, options, {}, false, records, take);
  REQUIRE(logs.size() == 2);
  REQUIRE(records.size() == 2);
  CHECK(records[0].file == a);
  CHECK(records[0].sha256 == Sha256Hex(a_text));
  CHECK(records[0].samples == 3);
  CHECK(records[1].samples == 2);
  CHECK(logs[1].columns[2] == std::vector<double>{7.0, 8.0});
  REQUIRE_FALSE(records[1].notes.empty());
  CHECK(records[1].notes.back() == "joined with " + j + " (sha256 " + Sha256Hex("u\n7\n8\n") + ")");

  records.clear();
  logs.clear();
  CHECK_THROWS_AS(ReadLogFiles({{a, "", {}}, {copy, "", {}}}, {"t", "q"}, options, {}, false, records, take),
                  OptionError);
  CHECK_THROWS_WITH(ReadLogFiles({{a, "", {}}, {copy, "", {}}}, {"t", "q"}, options, {}, false, records, take),
                    Catch::Contains(copy + ": the same data as " + a) && Catch::Contains("give each log once"));

  ReadLimits small;
  small.max_bytes = 8;
  small.max_bytes_hint = "raise the limit";
  CHECK_THROWS_WITH(ReadLogFiles({{a, "", {}}}, {"t", "q"}, options, small, false, records, take),
                    Catch::Contains("raise the limit"));
  std::filesystem::remove_all(dir);
}
