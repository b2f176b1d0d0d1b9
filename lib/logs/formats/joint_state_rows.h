// The messages of one sensor_msgs/JointState topic as a bag is streamed
// (docs/formats.md#ros-bags), kept compactly: what every message says about
// its joints (names, which arrays it fills) is counted, and only the times
// and values of the joints asked for are kept — per kept message two 64-bit
// times, a byte of flags and three doubles per kept joint — so that memory
// follows the samples kept, not the bag.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "logs/formats/joint_state_message.h"

namespace driveid {

class JointStateRows {
 public:
  /// `keep`: the joints whose values are kept, in this order; a message
  /// without one of them is counted, not kept. Empty with `all`: every
  /// joint, as first seen (a message without a joint gets NaN for it).
  /// Empty without `all`: nothing is kept, messages are only counted.
  JointStateRows(std::vector<std::string> keep, bool all);

  /// Takes one message (receive_ns and stamp_ns set).
  void Add(const JointStateMessage& message);

  /// Every joint seen, first-seen order, with the count of messages naming it.
  const std::vector<std::pair<std::string, std::size_t>>& joints_seen() const { return seen_; }
  std::size_t messages() const { return messages_; }
  /// Messages with a non-empty position, velocity, effort array.
  const std::array<std::size_t, 3>& filled() const { return filled_; }
  /// Messages left out for want of a joint in `keep`.
  std::size_t without() const { return without_; }

  /// The kept joints and, per kept message, the times, the flags (bit f:
  /// array f — position, velocity, effort — has one value per name) and per
  /// kept joint and field the values; taken by the table.
  std::vector<std::string> kept;
  std::vector<std::int64_t> stamp_ns, receive_ns;
  std::vector<std::uint8_t> flags;
  std::vector<std::array<std::vector<double>, 3>> values;

 private:
  std::size_t Slot(const std::string& joint);
  bool all_;
  std::vector<std::pair<std::string, std::size_t>> seen_;
  std::size_t messages_ = 0, without_ = 0;
  std::array<std::size_t, 3> filled_{};
  // The last message's names and, per name, its seen_ index and kept index
  // (npos: not kept): consecutive messages mostly name the same joints.
  std::vector<std::string> last_names_;
  std::vector<std::size_t> last_seen_, last_kept_, at_;
};

}  // namespace driveid
