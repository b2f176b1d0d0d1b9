// A JointState topic of a ROS bag (logs/formats/ros_bag.h; docs/formats.md#ros-bags)
// as a table (logs/formats/ros_source.h): rows are the topic's messages that carry every chosen joint,
// in time order; columns `stamp` (header.stamp [s]), `receive` (the bag's
// receive time [s]) and per joint J `J.position`, `J.velocity`, `J.effort`
// where every row carries them. `t` is `stamp` (or `receive`), and with one
// joint chosen (or only one in the topic) q, qd and tau are its position,
// velocity and effort. What was left out is named in the notes: messages
// without a chosen joint, out of order, at a repeated time, fields empty in
// some messages, and how far the two clocks differ.
#include "logs/formats/ros_source.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdint>
#include <cmath>
#include <map>
#include <numeric>
#include <set>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/order_statistics.h"
#include "logs/formats/joint_state_rows.h"
#include "system/byte_source.h"

namespace driveid {

// The nearest double to `ns` nanoseconds in seconds, as a CSV's
// "1705910000.123456789" is read: below 2^53 one division of exact operands
// (correctly rounded); above (stamps since 1970 are about 1.7e18 ns) the
// count converted to a double is already rounded, and dividing that rounds
// again (one stamp in four came out one ulp off), so its decimal text is read.
double NearestSeconds(std::int64_t ns) {
  constexpr std::int64_t kExact = std::int64_t{1} << 53;
  if (ns > -kExact && ns < kExact) return static_cast<double>(ns) / 1e9;
  char text[32];
  char* p = text;
  std::uint64_t magnitude = ns < 0 ? 0 - static_cast<std::uint64_t>(ns) : static_cast<std::uint64_t>(ns);
  if (ns < 0) *p++ = '-';
  const std::uint64_t seconds = magnitude / 1000000000u, fraction = magnitude % 1000000000u;
  p = std::to_chars(p, text + sizeof text, seconds).ptr;
  *p++ = '.';
  char digits[9];
  std::uint64_t rest = fraction;
  for (int i = 8; i >= 0; --i, rest /= 10) digits[i] = static_cast<char>('0' + rest % 10);
  p = std::copy(digits, digits + 9, p);
  double value = 0.0;
  std::from_chars(text, p, value);
  return value;
}

namespace {

constexpr const char* kJointState = "sensor_msgs/msg/JointState";

// The joints whose values are kept: those asked for, in order.
// `‹joint› all`: every joint that every message carries (a serial robot's).
bool AllJointsAsked(const LogSelection& format) {
  return (format.bag.joints.size() == 1 && format.bag.joints.front() == "all") ||
         (format.bag.every_joint && format.bag.joints.empty() && format.bag.joint_motor.empty() && format.bag.joint_link.empty());
}

std::vector<std::string> JointsAsked(const LogSelection& format) {
  if (AllJointsAsked(format)) return {};
  std::vector<std::string> joints = format.bag.joints;
  for (const std::string* j : {&format.bag.joint_motor, &format.bag.joint_link}) {
    if (!j->empty() && std::find(joints.begin(), joints.end(), *j) == joints.end()) joints.push_back(*j);
  }
  return joints;
}

// The kept messages' order: by time, stable, with a repeated time left out
// (empty: they are in order already, without a repeat); what was done is noted.
std::vector<std::size_t> RowOrder(const std::vector<std::int64_t>& time, bool receive, std::vector<std::string>& notes) {
  std::size_t disorder = 0, repeats = 0;
  for (std::size_t k = 1; k < time.size(); ++k) {
    disorder += time[k] < time[k - 1];
    repeats += time[k] == time[k - 1];
  }
  if (disorder == 0 && repeats == 0) return {};
  std::vector<std::size_t> order(time.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  if (disorder > 0) {
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return time[a] < time[b]; });
    notes.push_back(fmt::format("{} messages out of time order: sorted by {}", disorder, receive ? "receive time" : "header stamp"));
  }
  const std::size_t before = order.size();
  order.erase(std::unique(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return time[a] == time[b]; }),
              order.end());
  if (order.size() < before) {
    notes.push_back(fmt::format("{} {} messages at a repeated time left out", kReaderWarning, before - order.size()));
  }
  return order;
}

// `values` in `order` (freed after; `order` empty: as they are): a column
// of times in seconds (NearestSeconds).
std::vector<double> Reordered(std::vector<std::int64_t>& values, const std::vector<std::size_t>& order) {
  std::vector<double> out;
  out.reserve(values.size());
  if (order.empty()) {
    for (const std::int64_t v : values) out.push_back(NearestSeconds(v));
  } else {
    for (const std::size_t k : order) out.push_back(NearestSeconds(values[k]));
  }
  std::vector<std::int64_t>().swap(values);
  return out;
}
std::vector<double> Reordered(std::vector<double>& values, const std::vector<std::size_t>& order) {
  if (order.empty()) return std::move(values);
  std::vector<double> out;
  out.reserve(order.size());
  for (const std::size_t k : order) out.push_back(values[k]);
  std::vector<double>().swap(values);
  return out;
}

// The table of the kept joints (all joints of every message when none was asked for).
std::unique_ptr<TableSource> JointTable(const std::string& path, const std::string& topic, JointStateRows rows,
                                        const LogSelection& format, std::vector<std::string> notes) {
  std::vector<std::string> all;
  for (const auto& [name, count] : rows.joints_seen()) all.push_back(name);
  const std::vector<std::string> asked = JointsAsked(format);
  for (const auto& j : asked) ChooseName(all, j, "joint", "joint", path + " " + topic);
  if (asked.empty() && all.size() > 1 && !format.catalog && !AllJointsAsked(format)) {
    throw OptionError(fmt::format("{}: topic {} carries {} joints ({}): give ‹joint› NAME (repeat it for several, and "
                                  "map them with ‹col› q_motor=NAME.position ...), or ‹joint› all for a serial robot",
                                  path, topic, all.size(), fmt::join(all, ", ")));
  }
  std::vector<std::string> joints = asked;
  if (joints.empty()) {
    for (const auto& [name, count] : rows.joints_seen()) {
      if (count == rows.messages()) joints.push_back(name);
    }
  }
  notes.insert(notes.begin(), fmt::format("ROS bag topic {} ({}), {} messages", topic, kJointState, rows.messages()));
  if (rows.without() > 0) {
    notes.push_back(fmt::format("{} {} messages without {} left out", kReaderWarning, rows.without(), fmt::join(joints, ", ")));
  }
  const bool receive = format.bag.time == "receive";
  const std::vector<std::size_t> order = RowOrder(receive ? rows.receive_ns : rows.stamp_ns, receive, notes);
  const std::size_t n = order.empty() ? rows.stamp_ns.size() : order.size();
  const auto row = [&](std::size_t i) { return order.empty() ? i : order[i]; };
  if (n < 2) {
    throw InputError(fmt::format("{}: topic {} holds {} message{} with {}", path, topic, n, n == 1 ? "" : "s",
                                 fmt::join(joints, ", ")));
  }
  {
    std::vector<double> lag(n);
    for (std::size_t i = 0; i < n; ++i) lag[i] = static_cast<double>(rows.receive_ns[row(i)] - rows.stamp_ns[row(i)]) * 1e-9;
    const auto [low, high] = std::minmax_element(lag.begin(), lag.end());
    notes.push_back(fmt::format("time t: the {}; receive time - header stamp: median {:.6g} s (range {:.6g} .. {:.6g} s)",
                                receive ? "bag's receive times (‹time› receive)" : "header stamps", Median(lag), *low, *high));
  }
  std::vector<std::string> names = {"stamp", "receive"};
  std::vector<std::vector<double>> columns;
  columns.push_back(Reordered(rows.stamp_ns, order));
  columns.push_back(Reordered(rows.receive_ns, order));
  std::map<std::string, std::string> defaults = {{"t", receive ? "receive" : "stamp"}};
  const std::array<const char*, 3> fields = {"position", "velocity", "effort"}, logicals = {"q", "qd", "tau"};
  for (const auto& j : joints) {
    const std::size_t slot = static_cast<std::size_t>(std::find(rows.kept.begin(), rows.kept.end(), j) - rows.kept.begin());
    for (std::size_t f = 0; f < 3; ++f) {
      std::size_t carrying = 0;
      for (std::size_t i = 0; i < n; ++i) carrying += (rows.flags[row(i)] >> f & 1) != 0;
      if (carrying != n) {
        if (carrying > 0) notes.push_back(fmt::format("{}.{} is in {} of {} messages: not a column", j, fields[f], carrying, n));
        continue;
      }
      const std::string column = j + "." + fields[f];
      const std::string logical = logicals[f];
      names.push_back(column);
      columns.push_back(Reordered(rows.values[slot][f], order));
      if (joints.size() == 1) defaults[logical] = column;
      // ‹joint› all, a serial robot's columns (logs/serial_robot_log.h): q_J,
      // qd_J, tau_J (not otherwise: tau_link is an elastic joint's shaft torque).
      if (AllJointsAsked(format)) defaults[logical + "_" + j] = column;
      // The elastic joint: the motor joint's effort is the motor torque.
      if (j == format.bag.joint_motor) defaults[logical == "tau" ? "tau" : logical + "_motor"] = column;
      if (j == format.bag.joint_link && logical != "tau") defaults[logical + "_link"] = column;
    }
  }
  return MakeMemorySource({path, topic, "rosbag", "", "", std::move(names), std::move(columns), std::move(notes),
                          std::move(defaults), {}});
}

// Where a bag's JointState topics go: the one asked for (or, when none is,
// the first met) keeps its joints' values; every other is counted when the
// catalog lists them, else left undecoded.
class Sinks {
 public:
  explicit Sinks(const LogSelection& format) : format_(format) {}
  JointStateRows* operator()(const std::string& topic) {
    const bool chosen = format_.bag.topic.empty() ? rows_.empty() : topic == format_.bag.topic;
    if (!chosen && !format_.catalog) return nullptr;
    auto& slot = rows_[topic];
    slot = std::make_unique<JointStateRows>(chosen ? JointsAsked(format_) : std::vector<std::string>{}, chosen);
    if (chosen) chosen_ = topic;
    return slot.get();
  }
  JointStateRows* find(const std::string& topic) {
    const auto found = rows_.find(topic);
    return found != rows_.end() ? found->second.get() : nullptr;
  }
  const std::string& chosen() const { return chosen_; }

 private:
  const LogSelection& format_;
  std::map<std::string, std::unique_ptr<JointStateRows>> rows_;
  std::string chosen_;
};

}  // namespace

std::vector<std::unique_ptr<TableSource>> OpenRosBagSources(const std::string& path, const std::string& text,
                                                            const LogSelection& format, const BagContainer& container) {
  std::unique_ptr<ByteSource> bytes;
  if (!format.stream_file.empty()) bytes = OpenFileBytes(format.stream_file);
  if (!bytes) bytes = MemoryBytes(path, text);
  Sinks sinks(format);
  const JointStateSinks take = [&](const std::string& topic) { return sinks(topic); };
  const std::vector<RosTopic> topics = container.read(*bytes, take);
  std::vector<std::string> file_notes;
  if (container.file_notes) file_notes = container.file_notes(*bytes);
  std::vector<std::string> joint_topics;
  for (const auto& t : topics) {
    if (t.type == kJointState && (t.serialization == "cdr" || t.serialization == "ros1")) joint_topics.push_back(t.name);
  }
  std::vector<std::unique_ptr<TableSource>> out;
  const auto table = [&](const std::string& topic) {
    JointStateRows* rows = sinks.find(topic);
    if (rows == nullptr || topic != sinks.chosen()) {
      throw InputError(fmt::format("{}: JointState topic {} has no message", path, topic));
    }
    return JointTable(path, topic, std::move(*rows), format, file_notes);
  };
  if (format.catalog) {
    std::vector<SourceVariable> variables;
    std::vector<std::string> notes = {
        fmt::format("{} bag, {} topics", container.label, topics.size())};
    for (const auto& t : topics) {
      const double span = static_cast<double>(t.last_ns - t.first_ns) * 1e-9;
      std::string address = fmt::format("{} ({}), {} messages", t.type, t.serialization, t.messages);
      if (t.messages > 1 && span > 0.0) address += fmt::format(", {:.4g} Hz over {:.4g} s", static_cast<double>(t.messages - 1) / span, span);
      if (const JointStateRows* rows = sinks.find(t.name)) {
        std::vector<std::string> joints;
        for (const auto& [name, count] : rows->joints_seen()) joints.push_back(fmt::format("{} ({})", name, count));
        notes.push_back(fmt::format("{}: joints {}; position in {}, velocity in {}, effort in {} of {} messages", t.name,
                                    fmt::join(joints, ", "), rows->filled()[0], rows->filled()[1], rows->filled()[2],
                                    rows->messages()));
      }
      variables.push_back({t.name, t.messages, 1, address});
    }
    out.push_back(MakeMemorySource({path, "", "rosbag", "", "", {}, {}, std::move(notes), {}, std::move(variables)}));
    try {
      out.push_back(table(ChooseName(joint_topics, format.bag.topic, "JointState topic", "topic", path)));
    } catch (const OptionError&) {
    }
    return out;
  }
  out.push_back(table(ChooseName(joint_topics, format.bag.topic, "JointState topic", "topic", path)));
  return out;
}

LogFormat BagLogFormat(std::string name, std::function<bool(std::string_view head)> sniff, BagContainer container) {
  LogFormat format;
  format.name = std::move(name);
  format.source = "rosbag";
  format.kind = "a ROS bag";
  format.sniff = std::move(sniff);
  format.structured = true;
  format.streamed = true;
  const std::string refusal = "‹{option}›: {path} is no ROS bag; ‹{option}› chooses in a bag's JointState topic";
  for (const char* option : {"topic", "joint", "joint_motor", "joint_link", "time"}) {
    format.options.push_back(option);
    format.declared.push_back({option, refusal});
  }
  format.catalog = {"the bag's topics; a JointState topic follows as the source a fit reads", "topic", "messages",
                    "type (serialisation), messages, mean rate over the span"};
  format.open = [container = std::move(container)](const std::string& path, const std::string& text, const CsvFormat&,
                                                   const LogSelection& selection) {
    return OpenRosBagSources(path, text, selection, container);
  };
  return format;
}

}  // namespace driveid
