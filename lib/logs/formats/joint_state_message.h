// What every bag reader gives the table (docs/formats.md#ros-bags): its
// topics, and each sensor_msgs/JointState message decoded, handed to the
// rows its topic's sink keeps (logs/formats/joint_state_rows.h).
#pragma once

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace driveid {

/// A topic of a bag: name, message type, serialisation, and its messages'
/// count and receive-time span [ns].
struct RosTopic {
  std::string name, type, serialization;
  std::size_t messages = 0;
  std::int64_t first_ns = 0, last_ns = 0;
};

/// One JointState message as recorded.
struct JointStateMessage {
  std::int64_t receive_ns = 0;  ///< the bag's timestamp (when the recorder received it)
  std::int64_t stamp_ns = 0;    ///< header.stamp
  std::vector<std::string> name;
  std::vector<double> position, velocity, effort;
};

/// Why a message does not decode, without the place (its reader adds it).
struct MessageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class JointStateRows;

/// Asked once per JointState topic met (sensor_msgs JointState in CDR or ROS 1
/// serialisation): where its messages go, nullptr to leave them undecoded.
using JointStateSinks = std::function<JointStateRows*(const std::string& topic)>;

}  // namespace driveid
