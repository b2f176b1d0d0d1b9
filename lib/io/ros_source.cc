// A JointState topic of a ROS bag (io/ros_bag.h; docs/formats.md#ros-bags)
// as a table: rows are the topic's messages that carry every chosen joint,
// in time order; columns `stamp` (header.stamp [s]), `receive` (the bag's
// receive time [s]) and per joint J `J.position`, `J.velocity`, `J.effort`
// where every row carries them. `t` is `stamp` (or `receive`), and with one
// joint chosen (or only one in the topic) q, qd and tau are its position,
// velocity and effort. What was left out is named in the notes: messages
// without a chosen joint, out of order, at a repeated time, fields empty in
// some messages, and how far the two clocks differ.
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/order_statistics.h"
#include "io/mcap.h"
#include "io/ros1_bag.h"
#include "io/ros_bag.h"
#include "io/table_source.h"

namespace driveid {
namespace {

constexpr const char* kJointState = "sensor_msgs/msg/JointState";

std::size_t IndexOf(const std::vector<std::string>& names, const std::string& name) {
  return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
}

// The joints of a topic in first-seen order, with the messages carrying each.
std::vector<std::pair<std::string, std::size_t>> JointsSeen(const std::vector<JointStateMessage>& messages) {
  std::vector<std::pair<std::string, std::size_t>> out;
  for (const auto& m : messages) {
    for (const auto& n : m.name) {
      auto found = std::find_if(out.begin(), out.end(), [&](const auto& p) { return p.first == n; });
      if (found == out.end()) out.emplace_back(n, 1);
      else ++found->second;
    }
  }
  return out;
}


// The table of the chosen joints (all joints of every message when none).
std::unique_ptr<TableSource> JointTable(const std::string& path, const std::string& topic,
                                        std::vector<JointStateMessage> messages, const SysIdFormat& format,
                                        std::vector<std::string> notes) {
  const auto seen = JointsSeen(messages);
  std::vector<std::string> joints = format.joints;
  for (const std::string* j : {&format.joint_motor, &format.joint_link}) {
    if (!j->empty() && std::find(joints.begin(), joints.end(), *j) == joints.end()) joints.push_back(*j);
  }
  std::vector<std::string> all;
  for (const auto& [name, count] : seen) all.push_back(name);
  for (const auto& j : joints) ChooseName(all, j, "joint", "joint", path + " " + topic);
  if (joints.empty() && all.size() > 1 && !format.catalog) {
    throw OptionError(fmt::format("{}: topic {} carries {} joints ({}): give ‹joint› NAME (repeat it for several, and "
                                  "map them with ‹col› q_motor=NAME.position ...)",
                                  path, topic, all.size(), fmt::join(all, ", ")));
  }
  if (joints.empty()) {
    for (const auto& [name, count] : seen) {
      if (count == messages.size()) joints.push_back(name);
    }
  }
  notes.insert(notes.begin(), fmt::format("ROS bag topic {} ({}), {} messages", topic, kJointState, messages.size()));
  // Rows: the messages that carry every chosen joint.
  std::vector<JointStateMessage> rows;
  std::size_t without = 0;
  for (auto& m : messages) {
    const bool carries = std::all_of(joints.begin(), joints.end(), [&](const std::string& j) {
      return IndexOf(m.name, j) < m.name.size();
    });
    if (carries) rows.push_back(std::move(m));
    else ++without;
  }
  if (without > 0) notes.push_back(fmt::format("{} {} messages without {} left out", kReaderWarning, without, fmt::join(joints, ", ")));
  const bool receive = format.time == "receive";
  const auto time_of = [&](const JointStateMessage& m) { return receive ? m.receive_ns : m.stamp_ns; };
  std::size_t disorder = 0;
  for (std::size_t k = 1; k < rows.size(); ++k) disorder += time_of(rows[k]) < time_of(rows[k - 1]);
  std::stable_sort(rows.begin(), rows.end(), [&](const auto& a, const auto& b) { return time_of(a) < time_of(b); });
  if (disorder > 0) notes.push_back(fmt::format("{} messages out of time order: sorted by {}", disorder, receive ? "receive time" : "header stamp"));
  std::size_t repeated = 0;
  rows.erase(std::unique(rows.begin(), rows.end(), [&](const auto& a, const auto& b) {
               const bool same = time_of(a) == time_of(b);
               repeated += same;
               return same;
             }),
             rows.end());
  if (repeated > 0) notes.push_back(fmt::format("{} {} messages at a repeated time left out", kReaderWarning, repeated));
  if (rows.size() < 2) {
    throw InputError(fmt::format("{}: topic {} holds {} message{} with {}", path, topic, rows.size(),
                                 rows.size() == 1 ? "" : "s", fmt::join(joints, ", ")));
  }
  std::vector<double> lag;
  for (const auto& m : rows) lag.push_back(static_cast<double>(m.receive_ns - m.stamp_ns) * 1e-9);
  notes.push_back(fmt::format("time t: the {}; receive time - header stamp: median {:.6g} s (range {:.6g} .. {:.6g} s)",
                              receive ? "bag's receive times (‹time› receive)" : "header stamps", Median(lag),
                              *std::min_element(lag.begin(), lag.end()), *std::max_element(lag.begin(), lag.end())));
  std::vector<std::string> names = {"stamp", "receive"};
  std::vector<std::vector<double>> columns(2);
  for (const auto& m : rows) {
    // Divided, not multiplied by 1e-9: the nearest double to the time, as a
    // CSV's "0.001" is read.
    columns[0].push_back(static_cast<double>(m.stamp_ns) / 1e9);
    columns[1].push_back(static_cast<double>(m.receive_ns) / 1e9);
  }
  std::map<std::string, std::string> defaults = {{"t", receive ? "receive" : "stamp"}};
  for (const auto& j : joints) {
    for (const auto& [field, member, logical] :
         {std::tuple{"position", &JointStateMessage::position, "q"}, std::tuple{"velocity", &JointStateMessage::velocity, "qd"},
          std::tuple{"effort", &JointStateMessage::effort, "tau"}}) {
      std::vector<double> values;
      std::size_t carrying = 0;
      for (const auto& m : rows) {
        const std::size_t k = IndexOf(m.name, j);
        const auto& array = m.*member;
        if (array.size() == m.name.size()) {
          ++carrying;
          values.push_back(array[k]);
        }
      }
      if (carrying != rows.size()) {
        if (carrying > 0) notes.push_back(fmt::format("{}.{} is in {} of {} messages: not a column", j, field, carrying, rows.size()));
        continue;
      }
      names.push_back(j + "." + field);
      columns.push_back(std::move(values));
      const std::string column = j + "." + field;
      if (joints.size() == 1) defaults[logical] = column;
      // The elastic joint: the motor joint's effort is the motor torque.
      if (j == format.joint_motor) defaults[std::string(logical) == "tau" ? "tau" : std::string(logical) + "_motor"] = column;
      if (j == format.joint_link && std::string(logical) != "tau") defaults[std::string(logical) + "_link"] = column;
    }
  }
  return MakeMemorySource({path, topic, "rosbag", "", "", std::move(names), std::move(columns), std::move(notes),
                          std::move(defaults), {}});
}

}  // namespace

std::vector<std::unique_ptr<TableSource>> OpenRosBagSources(const std::string& path, const std::string& text,
                                                            const SysIdFormat& format) {
  const bool mcap = LooksLikeMcap(text), ros1 = LooksLikeRos1Bag(text);
  const auto read_topic = [&](const std::string& topic) {
    return mcap ? ReadMcapJointStates(path, text, topic)
           : ros1 ? ReadRos1JointStates(path, text, topic)
                  : ReadSqliteJointStates(path, text, topic);
  };
  const std::vector<RosTopic> topics = mcap ? ReadMcapTopics(path, text)
                                       : ros1 ? ReadRos1Topics(path, text)
                                              : ReadSqliteTopics(path, text);
  std::vector<std::string> file_notes;
  if (mcap && !McapComplete(text)) {
    file_notes.push_back(fmt::format("{} the MCAP file ends without its closing magic: cut while it was written? "
                                     "(its records up to the cut are read)",
                                     kReaderWarning));
  }
  std::vector<std::string> joint_topics;
  for (const auto& t : topics) {
    if (t.type == kJointState) joint_topics.push_back(t.name);
  }
  std::vector<std::unique_ptr<TableSource>> out;
  if (format.catalog) {
    std::map<std::string, std::vector<JointStateMessage>> decoded;  // read once, for the notes and the table
    std::vector<SourceVariable> variables;
    std::vector<std::string> notes = {
        fmt::format("{} bag, {} topics", mcap ? "rosbag2 MCAP" : ros1 ? "ROS 1 (2.0)" : "rosbag2 SQLite3", topics.size())};
    for (const auto& t : topics) {
      const double span = static_cast<double>(t.last_ns - t.first_ns) * 1e-9;
      std::string address = fmt::format("{} ({}), {} messages", t.type, t.serialization, t.messages);
      if (t.messages > 1 && span > 0.0) address += fmt::format(", {:.4g} Hz over {:.4g} s", static_cast<double>(t.messages - 1) / span, span);
      if (t.type == kJointState && (t.serialization == "cdr" || t.serialization == "ros1")) {
        const auto& messages = decoded[t.name] = read_topic(t.name);
        std::vector<std::string> joints;
        for (const auto& [name, count] : JointsSeen(messages)) joints.push_back(fmt::format("{} ({})", name, count));
        std::size_t p = 0, v = 0, e = 0;
        for (const auto& m : messages) {
          p += !m.position.empty();
          v += !m.velocity.empty();
          e += !m.effort.empty();
        }
        notes.push_back(fmt::format("{}: joints {}; position in {}, velocity in {}, effort in {} of {} messages", t.name,
                                    fmt::join(joints, ", "), p, v, e, messages.size()));
      }
      variables.push_back({t.name, t.messages, 1, address});
    }
    out.push_back(MakeMemorySource({path, "", "rosbag", "", "", {}, {}, std::move(notes), {}, std::move(variables)}));
    try {
      const std::string topic = ChooseName(joint_topics, format.topic, "JointState topic", "topic", path);
      const auto found = decoded.find(topic);
      out.push_back(JointTable(path, topic, found != decoded.end() ? std::move(found->second) : read_topic(topic), format,
                               file_notes));
    } catch (const OptionError&) {
    }
    return out;
  }
  const std::string topic = ChooseName(joint_topics, format.topic, "JointState topic", "topic", path);
  out.push_back(JointTable(path, topic, read_topic(topic), format, file_notes));
  return out;
}

}  // namespace driveid
