// logs/log_selection.h: what each format family is told. By default nothing
// is selected (a bag's time base is its header stamps), and every field a
// user sets is seen by the registry under its option's name, so that a
// file of a format that does not take it is refused by that name
// (GivenSelectionOptions, logs/log_format.h).
#include <map>
#include <string>

#include <catch2/catch.hpp>

#include "logs/log_format.h"
#include "logs/log_selection.h"

using namespace driveid;

TEST_CASE("log selection: the defaults select nothing; every given field is seen by its option's name") {
  const LogSelection none;
  CHECK(none.bag.time == std::string(kDefaultBagTime));
  CHECK(std::string(kDefaultBagTime) == "header");
  CHECK(GivenSelectionOptions(none).empty());
  LogSelection all;
  all.sysid.side = "left";
  all.wpilog.mechanism = "shooter";
  all.wpilog.motor = "leader";
  all.wpilog.test = "arm";
  all.bag.topic = "/joint_states";
  all.bag.joints = {"a", "b"};
  all.bag.time = "receive";
  all.bag.joint_motor = "m";
  all.bag.joint_link = "l";
  std::map<std::string, std::string> given;
  for (const auto& [name, value] : GivenSelectionOptions(all)) given[name] = value;
  const std::map<std::string, std::string> expected = {
      {"side", "left"},  {"mechanism", "shooter"}, {"motor", "leader"}, {"test", "arm"},        {"topic", "/joint_states"},
      {"joint", "a,b"},  {"time", "receive"},      {"joint_motor", "m"}, {"joint_link", "l"}};
  CHECK(given == expected);
  // Not selections: reading every joint of a bag, a catalog, a streamed file.
  LogSelection reading;
  reading.bag.every_joint = true;
  reading.catalog = true;
  reading.stream_file = "bag.db3";
  CHECK(GivenSelectionOptions(reading).empty());
}
