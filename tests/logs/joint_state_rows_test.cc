// What a streamed JointState topic keeps (logs/formats/joint_state_rows.h): the joints
// asked for, from the messages that name them all; every joint with NaN
// where a message lacks it when all are kept; counts only when none is; the
// joints seen with their message counts (a name twice in one message counts
// once) and the arrays filled, whatever is kept.
#include "logs/formats/joint_state_rows.h"

#include <cmath>

#include <catch2/catch.hpp>

using namespace driveid;

namespace {

JointStateMessage Message(std::int64_t t, std::vector<std::string> names, std::vector<double> position,
                          std::vector<double> velocity, std::vector<double> effort) {
  JointStateMessage m;
  m.stamp_ns = t;
  m.receive_ns = t + 3;
  m.name = std::move(names);
  m.position = std::move(position);
  m.velocity = std::move(velocity);
  m.effort = std::move(effort);
  return m;
}

void AddAll(JointStateRows& rows) {
  rows.Add(Message(10, {"a", "b"}, {1, 2}, {}, {5, 6}));
  rows.Add(Message(20, {"b", "a"}, {3, 4}, {7, 8}, {9, 10}));
  rows.Add(Message(30, {"b"}, {11}, {}, {12}));
  rows.Add(Message(40, {"a", "a"}, {13, 14}, {}, {15}));  // a named twice; effort not one per name
}

}  // namespace

TEST_CASE("the joints asked for are kept from the messages that name them all") {
  JointStateRows rows({"a"}, false);
  AddAll(rows);
  CHECK(rows.messages() == 4);
  CHECK(rows.without() == 1);
  CHECK(rows.kept == std::vector<std::string>{"a"});
  CHECK(rows.stamp_ns == std::vector<std::int64_t>{10, 20, 40});
  CHECK(rows.receive_ns == std::vector<std::int64_t>{13, 23, 43});
  CHECK(rows.values[0][0] == std::vector<double>{1, 4, 13});  // a's position, its first occurrence
  CHECK(rows.flags == std::vector<std::uint8_t>{0b101, 0b111, 0b001});
  CHECK(rows.values[0][2][0] == 5);
  CHECK(rows.values[0][2][1] == 10);
  CHECK(std::isnan(rows.values[0][2][2]));  // effort not filled for every name
  CHECK(std::isnan(rows.values[0][1][0]));
  const std::vector<std::pair<std::string, std::size_t>> seen = {{"a", 3}, {"b", 3}};
  CHECK(rows.joints_seen() == seen);
  CHECK(rows.filled() == std::array<std::size_t, 3>{4, 1, 4});
}

TEST_CASE("all joints: each as first seen, NaN where a message lacks it; none: counts only") {
  JointStateRows all({}, true);
  AddAll(all);
  CHECK(all.kept == std::vector<std::string>{"a", "b"});
  CHECK(all.stamp_ns.size() == 4);
  CHECK(all.without() == 0);
  CHECK(all.values[1][0][0] == 2);
  CHECK(all.values[1][0][1] == 3);
  CHECK(all.values[1][0][2] == 11);
  CHECK(std::isnan(all.values[1][0][3]));
  CHECK(std::isnan(all.values[0][0][2]));

  JointStateRows none({}, false);
  AddAll(none);
  CHECK(none.kept.empty());
  CHECK(none.stamp_ns.empty());
  CHECK(none.messages() == 4);
  CHECK(none.joints_seen() == all.joints_seen());
}
