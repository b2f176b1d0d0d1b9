// logs/table_source.h: a source's columns addressed by `#k` or by a name
// that occurs once (an ambiguous name refused with both positions), a log in
// memory read as a source, and ChooseName's refusals naming what the file
// offers.
#include <string>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "logs/table_source.h"

using namespace driveid;

TEST_CASE("table source: columns by position or by a name that occurs once") {
  MemorySourceParts parts;
  parts.path = "m.log";
  parts.format = "memory";
  parts.names = {"t", "q", "q", ""};
  parts.columns = {{0.0, 1.0}, {1.0, 2.0}, {3.0, 4.0}, {5.0, 6.0}};
  parts.defaults = {{"tau", "#4"}};
  const auto source = MakeMemorySource(parts);
  CHECK(source->Find("t") == std::size_t{0});
  CHECK(source->Find("#4") == std::size_t{3});
  CHECK_FALSE(source->Find("#5").has_value());
  CHECK_FALSE(source->Find("#0").has_value());
  CHECK_FALSE(source->Find("x").has_value());
  CHECK_THROWS_WITH(source->Find("q"), "m.log: column 'q' occurs at #2 and #3: name it by position");
  CHECK(source->DefaultReference("tau") == "#4");
  CHECK(source->DefaultReference("q").empty());
  const TableData data = source->Read({3, 0});
  REQUIRE(data.columns.size() == 2);
  CHECK(data.columns[0] == std::vector<double>{5.0, 6.0});
  CHECK(data.columns[1] == std::vector<double>{0.0, 1.0});
  CHECK(source->column_lengths() == std::vector<std::size_t>(4, 2));
}

TEST_CASE("ChooseName: the one wanted, else the only one; refusals name what the file offers") {
  const std::vector<std::string> motors = {"left", "right"};
  CHECK(ChooseName(motors, "right", "motor", "motor", "a.wpilog") == "right");
  CHECK(ChooseName({"only"}, "", "motor", "motor", "a.wpilog") == "only");
  CHECK_THROWS_WITH(ChooseName(motors, "front", "motor", "motor", "a.wpilog"),
                    "‹motor› front: a.wpilog has no such motor (found: left, right)");
  CHECK_THROWS_WITH(ChooseName(motors, "", "motor", "motor", "a.wpilog"),
                    "a.wpilog: 2 motors (left, right): give ‹motor›");
  CHECK_THROWS_AS(ChooseName({}, "", "motor", "motor", "a.wpilog"), InputError);
}
