// A log type's columns declared once (logs/log_columns.h), on a log type
// made up here: the reader's request, the log made from what was read, the
// CSV written and read back by the tools' own reader, and the writer's
// refusals (a non-finite value, a column of the wrong length).
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "logs/log_input.h"
#include "logs/log_columns.h"

namespace driveid {
namespace {

struct TestLog {
  std::string path;
  std::vector<double> t, q, aux;
};

constexpr LogColumn<TestLog> kColumns[] = {
    RequiredColumn<TestLog>("t", FieldOf<TestLog, &TestLog::t>, "{:.3f}"),
    RequiredColumn<TestLog>("q|pos", FieldOf<TestLog, &TestLog::q>, "{:.9g}"),
    RequiredColumn<TestLog>("i", nullptr),  // read for a maker, not stored as read
    OptionalColumn<TestLog>("aux", FieldOf<TestLog, &TestLog::aux>),
};
static_assert(LogColumnIndex(kColumns, "i") == 2);
static_assert(LogColumnIndex(kColumns, "q|pos") == 1);
static_assert(LogColumnIndex(kColumns, "nosuch") == 4);

TEST_CASE("the request, the log made from what was read, and the CSV read back") {
  CHECK(LogColumnRequest(kColumns) == std::vector<std::string>{"t", "q|pos", "i", "?aux"});
  // A file with the alternative name 'pos' and no 'aux'.
  CsvLog csv = ParseCsvLog("x.csv", "# c\nt,i,pos\n0,5,0.25\n0.5,6,-1e-7\n", LogColumnRequest(kColumns));
  const TestLog log = MakeLogFromColumns(kColumns, csv);
  CHECK(log.path == "x.csv");
  CHECK(log.t == std::vector<double>{0.0, 0.5});
  CHECK(log.q == std::vector<double>{0.25, -1e-7});
  CHECK(log.aux.empty());
  CHECK(csv.columns[2] == std::vector<double>{5.0, 6.0});  // not moved: no field
  // Written: the columns with a format, under their first name.
  const std::string text = FormatLogColumns(kColumns, log, {"made by a test"});
  CHECK(text == "# made by a test\nt,q\n0.000,0.25\n0.500,-1e-07\n");
  const CsvLog back = ParseCsvLog("y.csv", text, {"t", "q"});
  CHECK(back.column("q") == log.q);
}

TEST_CASE("the writer refuses a non-finite value and a column shorter or longer than the times") {
  TestLog log;
  log.t = {0.0, 1.0, 2.0};
  log.q = {1.0, std::nan(""), 3.0};
  CHECK_THROWS_WITH(FormatLogColumns(kColumns, log, {}), Catch::Contains("column 'q' would be nan at t = 1 s"));
  log.q = {1.0, 2.0};
  CHECK_THROWS_AS(FormatLogColumns(kColumns, log, {}), OutputError);
  CHECK_THROWS_WITH(FormatLogColumns(kColumns, log, {}), "column 'q' holds 2 values for 3 times; nothing written");
  log.q = {1.0, 2.0, 3.0, 4.0};
  CHECK_THROWS_WITH(FormatLogColumns(kColumns, log, {}), Catch::Contains("holds 4 values for 3 times"));
}

}  // namespace
}  // namespace driveid
