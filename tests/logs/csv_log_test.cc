#include "logs/formats/csv_source.h"
#include "logs/log_input.h"

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "logs/table_source.h"

using driveid::CsvReadOptions;
using driveid::InputError;
using driveid::ParseCsvLog;

namespace {
const std::vector<std::string> kStep = {"t", "tau_motor", "tau_link"};

std::string ErrorOf(const std::string& text, const CsvReadOptions& options = {}) {
  try {
    ParseCsvLog("log.csv", text, kStep, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}
}  // namespace

TEST_CASE("reads header, comments, CRLF and BOM") {
  const std::string text =
      "\xEF\xBB\xBF# made by hand\r\nt, tau_motor ,tau_link,extra\r\n0,0,0.5,x\r\n\r\n0.001,-0.8,1e-3,y\r\n";
  const auto log = ParseCsvLog("log.csv", text, kStep);
  REQUIRE(log.rows() == 2);
  CHECK(log.column("tau_motor")[1] == -0.8);
  CHECK(log.column("tau_link")[1] == 1e-3);
  CHECK(log.line_numbers[1] == 5);
  REQUIRE(log.comments.size() == 1);
  CHECK(log.comments[0] == " made by hand");
}

// RFC 4180 quoting (issue 71: a robot repository's own export quotes every
// field, and a header name holding the delimiter split into two columns).
TEST_CASE("quoted fields: delimiters inside are text, quotes around numbers and names are dropped") {
  const std::string text = "\"t\",\"tau_motor, Nm\", \"tau_link\" ,\"say \"\"hi\"\"\"\n"
                           "\"0\",\"1.5\",2,\"a, b\"\n"
                           "0.001,\"-0.5\",\"3\",x\n";
  CsvReadOptions options;
  options.column_map = driveid::ParseColumnMap({"tau_motor=tau_motor, Nm"});
  const auto log = ParseCsvLog("q.csv", text, kStep, options);
  REQUIRE(log.rows() == 2);
  CHECK(log.column("tau_motor")[0] == 1.5);
  CHECK(log.column("tau_motor")[1] == -0.5);
  CHECK(log.column("tau_link")[1] == 3.0);
  CHECK(log.column("t")[1] == 0.001);
  // A quote left open runs to the line's end: one field "1,2", not a number.
  CHECK_THAT(ErrorOf("t,tau_motor,tau_link\n0,\"1,2\n"), Catch::Contains("log.csv:2: column 'tau_motor': not a number"));
}

TEST_CASE("maps columns with --col") {
  CsvReadOptions options;
  options.column_map = driveid::ParseColumnMap({"tau_link=strain"});
  const auto log = ParseCsvLog("log.csv", "t,tau_motor,strain\n0,1,2\n", kStep, options);
  CHECK(log.column("tau_link")[0] == 2.0);
  CHECK_THROWS_AS(driveid::ParseColumnMap({"novalue"}), InputError);
}

TEST_CASE("irregular sampling is accepted, non-increasing time is not") {
  CHECK_NOTHROW(ParseCsvLog("log.csv", "t,tau_motor,tau_link\n0,0,0\n0.001,0,0\n0.0035,0,0\n", kStep));
  CHECK(ErrorOf("t,tau_motor,tau_link\n0,0,0\n0.001,0,0\n0.001,0,0\n") ==
        "log.csv:4: column 't': time not strictly increasing (0.001 after 0.001)");
}

TEST_CASE("every malformed input names file, line and column") {
  CHECK(ErrorOf("") == "log.csv: empty file: no header row");
  CHECK(ErrorOf("# only a comment\n") == "log.csv: empty file: no header row");
  CHECK(ErrorOf("t,tau_motor,tau_link\n") == "log.csv:1: no data rows after the header");
  CHECK_THAT(ErrorOf("t,tau_motor\n0,1\n"), Catch::StartsWith("log.csv:1: missing column 'tau_link'"));
  CHECK(ErrorOf("t,tau_motor,tau_link\n0,0,1.2.3\n") == "log.csv:2: column 'tau_link': not a number: \"1.2.3\"");
  CHECK(ErrorOf("t,tau_motor,tau_link\n0,nan,1\n") == "log.csv:2: column 'tau_motor': not a finite number: \"nan\"");
  CHECK(ErrorOf("t,tau_motor,tau_link\n0,0,inf\n") == "log.csv:2: column 'tau_link': not a finite number: \"inf\"");
  CHECK(ErrorOf("t,tau_motor,tau_link\n0,0,1e999\n") == "log.csv:2: column 'tau_link': number out of range: \"1e999\"");
  CHECK(ErrorOf("t,tau_motor,tau_link\n0,,1\n") == "log.csv:2: column 'tau_motor': empty cell");
  CHECK(ErrorOf("t,tau_motor,tau_link\n0,0\n") == "log.csv:2: 2 fields, but the header (line 1) has 3");
  CHECK(ErrorOf("t,tau_motor,tau_link\n0,0,1,4\n") == "log.csv:2: 4 fields, but the header (line 1) has 3");
  CHECK(ErrorOf("t,t,tau_link\n0,0,1\n") == "log.csv:1: column 't' appears twice in the header");
}

TEST_CASE("binary garbage and huge lines are refused without echoing them") {
  std::string garbage = "t,tau_motor,tau_link\n0,0,";
  for (int i = 0; i < 300; ++i) garbage += static_cast<char>(i % 256);
  const std::string error = ErrorOf(garbage);
  CHECK_THAT(error, Catch::StartsWith("log.csv:2: column 'tau_link': not a number: \"\\x00"));
  CHECK(error.size() < 400);
  const std::string huge = "t,tau_motor,tau_link\n0,0," + std::string(2 << 20, '1') + "\n";
  CHECK(ErrorOf(huge) == "log.csv:2: line longer than 1048576 bytes");
  CHECK_THAT(ErrorOf(std::string("\0\0\0\x01\x02", 5)), Catch::StartsWith("log.csv:1: no data rows"));
}

TEST_CASE("unreadable file") {
  CHECK_THROWS_WITH(driveid::ReadCsvLog("/nonexistent/x.csv", kStep),
                    "/nonexistent/x.csv: cannot open file for reading: No such file or directory");
}

TEST_CASE("alternatives: the first present column wins, names tell which") {
  const std::vector<std::string> wanted = {"t", "tau_L|i_L"};
  const auto with_torque = ParseCsvLog("c.csv", "t,i_L,tau_L\n0,1,2\n", wanted);
  CHECK(with_torque.names[1] == "tau_L");
  CHECK(with_torque.columns[1][0] == 2.0);
  const auto with_current = ParseCsvLog("c.csv", "t,i_L\n0,1\n", wanted);
  CHECK(with_current.names[1] == "i_L");
  CHECK(with_current.column("i_L")[0] == 1.0);
  CHECK_THROWS_WITH(ParseCsvLog("c.csv", "t,x\n0,1\n", wanted),
                    Catch::StartsWith("c.csv:1: missing column 'tau_L' or 'i_L' (header has"));
}

TEST_CASE("--skip-rows: a drive export's preamble before the header") {
  using driveid::CsvFormat;
  using driveid::OpenCsvSource;
  const std::string text =
      "Servo drive XY-200 Bode export\nAxis: 1, 2026-11-27 10:00\n\nfrequency,magnitude,phase\n1,2,3\n4,5,6\n";
  // Unskipped, the preamble is taken for the header and its rows differ.
  CHECK_THROWS_AS(OpenCsvSource("bode.csv", text, CsvFormat{})->Read({0, 1, 2}), InputError);
  CsvFormat format;
  format.skip_rows = 3;
  const auto source = OpenCsvSource("bode.csv", text, format);
  CHECK(source->column_names() == std::vector<std::string>{"frequency", "magnitude", "phase"});
  CHECK(source->header_line() == 4);
  const auto data = source->Read({0, 2});
  REQUIRE(data.columns[1].size() == 2);
  CHECK(data.columns[1][1] == 6.0);
  CHECK(data.line_numbers[1] == 6);
  REQUIRE(source->comments().size() == 3);
  CHECK(source->comments()[0] == "Servo drive XY-200 Bode export");
  // Every line skipped: refused by name, not read as empty.
  format.skip_rows = 10;
  CHECK_THROWS_WITH(OpenCsvSource("bode.csv", text, format), Catch::Contains("all skipped"));
}
