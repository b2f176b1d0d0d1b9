// MAT v7.3 (HDF5) cut short at every length: refused naming the file, or the
// same data as the whole file (issue 21; the v5 sweep is in
// log_input_test.cc). Prefixes that hold the superblock are refused before a
// reader process starts; the first ~520 start one each.
#include <string>

#include <catch2/catch.hpp>
#include <matio.h>

#include "core/errors.h"
#include "io/log_input.h"
#include "support/mat_fixture.h"

using namespace driveid;

TEST_CASE("MAT v7.3 cut short at every length: refused naming the file, or the same data as the whole file") {
  const std::string bytes = driveid::testing::WriteMat(MAT_FT_MAT73);
  const std::vector<std::string> columns = {"t", "q", "tau|i"};
  LogInputOptions options;
  options.columns = {{"q", "data(:,2)"}, {"i", "data(:,3)"}};
  const auto whole = ReadLogs("whole.mat", bytes, {}, columns, options);
  REQUIRE(whole.size() == 1);
  int refused = 0;
  for (std::size_t length = 0; length < bytes.size(); ++length) {
    try {
      const auto logs = ReadLogs("cut.mat", bytes.substr(0, length), {}, columns, options);
      INFO("prefix of " << length << " of " << bytes.size() << " bytes read");
      REQUIRE(logs.size() == 1);
      CHECK(logs[0].columns == whole[0].columns);
    } catch (const InputError& e) {
      INFO("prefix of " << length << " bytes: " << e.what());
      CHECK(std::string(e.what()).rfind("cut.mat", 0) == 0);
      ++refused;
    }
  }
  CHECK(refused > 0);
}
