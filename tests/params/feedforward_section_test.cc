// params/feedforward_section.h: the feed-forward section written by a fit
// reads back to its gains, std and units; a unit that could end its comment
// and start a key, an over-long unit, an unknown gain or law are refused
// naming the file, line and key.
#include <string>

#include <catch2/catch.hpp>
#include <yaml-cpp/yaml.h>

#include "core/errors.h"
#include "params/feedforward_section.h"

using namespace driveid;

namespace {

Feedforward Parse(const std::string& text) { return ParseFeedforward("f.yaml", YAML::Load(text)["feedforward"]); }

}  // namespace

TEST_CASE("feed-forward section: written, read back; units and keys refused by name") {
  Feedforward f;
  f.effort_unit = "V";
  f.position_unit = "Meters";
  f.gains = {{"Ks", 0.075, 0.03, ""}, {"Kv", 0.125, 0.0033, ""}, {"Ka", 1.0 / 3.0, 0.007, ""}};
  const Feedforward back = Parse(FormatFeedforward(f));
  CHECK(back.effort_unit == "V");
  CHECK(back.position_unit == "Meters");
  REQUIRE(back.gains.size() == 3);
  CHECK(back.gains[2].key == "Ka");
  CHECK(back.gains[2].value == 1.0 / 3.0);  // to the last bit
  CHECK(back.gains[1].standard_error == Approx(0.0033));
  CHECK(back.gains[1].unit == "V s/Meters");
  CHECK_THROWS_WITH(Parse("feedforward:\n  effort_unit: V\n  Kx: {value: 1}\n"),
                    Catch::Contains("f.yaml:3:3: feedforward.Kx: unknown key"));
  CHECK_THROWS_WITH(Parse("feedforward:\n  effort_unit: \"V\\n  Ks: 1\"\n"), Catch::Contains("not a unit name"));
  CHECK_THROWS_WITH(Parse("feedforward:\n  position_unit: " + std::string(65, 'm') + "\n"),
                    Catch::Contains("feedforward.position_unit: 65 bytes: at most 64"));
  CHECK_THROWS_WITH(Parse("feedforward:\n  law: pid\n"), Catch::Contains("feedforward.law: \"pid\": expected"));
  CHECK_THROWS_WITH(Parse("feedforward:\n  Kv: {std: 1}\n"), Catch::Contains("feedforward.Kv: needs a value"));
}
