// `inspect` (lib/workflow/log_inspection.h) of a MAT file with a struct: its
// variables and struct fields with sizes and addresses, columns on request;
// a log that cannot be read as a fit would read it says why, not "no time
// base" when the time base is fine.
#include "logs/formats/mat_source.h"
#include "logs/formats/csv_source.h"
#include "workflow/log_inspection.h"

#include <string>

#include <catch2/catch.hpp>

#include "logs/table_source.h"
#include "support/mat_fixture.h"

using namespace driveid;

namespace {
// The text with every run of blanks as one space (column widths vary with the names).
std::string Squeezed(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == ' ' && !out.empty() && out.back() == ' ') continue;
    out += c;
  }
  return out;
}
}  // namespace

TEST_CASE("inspect of a MAT file: variables and struct fields with sizes and addresses; columns with --columns") {
  const std::string bytes = driveid::testing::WriteMat(MAT_FT_MAT5);
  const auto source = OpenMatSource("m.mat", bytes);
  LogInputOptions options;
  options.columns = {{"q", "rec.pos(1,:)"}};
  const InspectedLog brief = InspectLog(*source, options);
  CHECK(brief.columns.empty());
  const std::string text = Squeezed(FormatLogInspection(brief));
  INFO(text);
  CHECK(text.find("rec.pos 2 x 5 rows rec.pos(1,:) .. rec.pos(2,:); columns rec.pos(:,k)") !=
        std::string::npos);
  CHECK(text.find("rec.time_cont 5 x 1 rec.time_cont (elements rec.time_cont(i) for expressions)") !=
        std::string::npos);
  CHECK(text.find("gain 1 x 1 gain = 2.5 (a scalar for expressions)") != std::string::npos);
  CHECK(text.find("inspect ‹columns›") != std::string::npos);
  CHECK(text.find("5 samples, t = 0 .. 0.04 s") != std::string::npos);
  CHECK(text.find("q = rec.pos(1,:)") != std::string::npos);
  const InspectedLog full = InspectLog(*source, options, true);
  REQUIRE_FALSE(full.columns.empty());
  CHECK(FormatLogInspection(full).find("rec.pos(2,:)") != std::string::npos);
  CHECK(LogInspectionJson(brief)["variables"].size() == brief.variables.size());
}

TEST_CASE("inspect: a column problem is not called a missing time base") {
  // --rate gives the time base; the problem is the column asked for.
  const std::string csv = "q,tau\n1,2\n2,3\n";
  const auto source = OpenCsvSource("rate.csv", csv, {});
  LogInputOptions options;
  options.rate = 100.0;
  options.columns = {{"q", "angle"}};
  const InspectedLog log = InspectLog(*source, options);
  CHECK_FALSE(log.has_time);
  const std::string text = FormatLogInspection(log);
  INFO(text);
  CHECK(text.find("no time base") == std::string::npos);
  CHECK(text.find("not readable as a fit would read it: ") != std::string::npos);
  CHECK(text.find("angle") != std::string::npos);
}

TEST_CASE("inspect: times since 1970 (a bag's) to the microsecond, not in 6 digits") {
  const std::string csv = "t,q,tau\n1705910000.125,1,2\n1705910000.625,2,3\n1705910001.125,3,4\n";
  const auto source = OpenCsvSource("epoch.csv", csv, {});
  const std::string text = FormatLogInspection(InspectLog(*source, LogInputOptions{}));
  INFO(text);
  CHECK(text.find("t = 1705910000.125000 .. 1705910001.125000 s (1 s)") != std::string::npos);
}
