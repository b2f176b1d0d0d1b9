// logs/axis_log.h: an axis log written by its formatter reads back to the values it
// held (to the written digits), comments first; a current is read as a force
// with k_t and refused without one, naming the file.
#include <catch2/catch.hpp>

#include "core/errors.h"
#include "logs/axis_log.h"
#include "support/log_values.h"

using namespace driveid;
using driveid::testing::CheckClose;
using driveid::testing::Ramp;

TEST_CASE("axis log: formatted, read back; a current times k_t, refused without it") {
  AxisLog log;
  log.path = "a.csv";
  log.time = Ramp(30, 0.0, 0.01);
  log.position = Ramp(30, 0.1, 0.02);
  log.force = Ramp(30, -1.0, 0.1);
  const std::string text = FormatAxisLog(log, {"made by a test", "truth: none"});
  CHECK(text.rfind("# made by a test\n# truth: none\n", 0) == 0);
  const AxisLog back = ParseAxisLog("a.csv", text, {}, 0.0);
  CheckClose(back.time, log.time);
  CheckClose(back.position, log.position);
  CheckClose(back.force, log.force);
  CHECK(back.rate.empty());
  const std::string current = "t,q,i\n0,0,1\n0.1,0.1,2\n0.2,0.2,3\n";
  CheckClose(ParseAxisLog("c.csv", current, {}, 0.5).force, {0.5, 1.0, 1.5});
  CHECK_THROWS_WITH(ParseAxisLog("c.csv", current, {}, 0.0), Catch::Contains("c.csv"));
}
