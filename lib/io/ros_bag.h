// ROS bags (docs/formats.md#ros-bags): a rosbag2 SQLite3 file (`.db3`, or
// its folder with metadata.yaml), read with libsqlite3, and
// `sensor_msgs/msg/JointState` messages decoded from CDR with libfastcdr.
// Every sequence length a message claims is checked against the bytes it
// has left before anything is allocated; a message that does not decode is
// refused with its topic, index and receive time.
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
class ByteSource;

/// Asked once per JointState topic met (sensor_msgs JointState in CDR or ROS 1
/// serialisation): where its messages go, nullptr to leave them undecoded.
using JointStateSinks = std::function<JointStateRows*(const std::string& topic)>;

/// True when `text` is an SQLite 3 database (a rosbag2 .db3).
bool LooksLikeSqlite(const std::string& text);

/// The file a log path names: itself, or for a rosbag2 folder the storage
/// file its metadata.yaml lists (or its one .db3/.mcap); InputError for a
/// folder that is no bag or a bag split over several files.
std::string ResolveBagPath(const std::string& path);

/// Reads a rosbag2 SQLite3 bag (from memory with sqlite3_deserialize, from
/// a file by its path, opened read-only and immutable): its topics, and the
/// messages of the JointState topics `sinks` takes, in the bag's order.
std::vector<RosTopic> ReadSqliteBag(ByteSource& bytes, const JointStateSinks& sinks);

/// Inflates an lz4 frame (MCAP and ROS 1 bag chunks) into `out`, sized to
/// the bytes it claims; "" on success, else liblz4's reason (or that the
/// frame holds more than `out` can take).
std::string InflateLz4Frame(const char* data, std::size_t size, std::string& out);

/// Decodes a CDR-serialised sensor_msgs/msg/JointState (with its 4-byte
/// encapsulation header) into `into` (its arrays' storage reused); throws
/// MessageError.
void DecodeJointStateCdr(const char* data, std::size_t size, JointStateMessage& into);
/// The same, throwing InputError "where: why".
JointStateMessage DecodeJointStateCdr(const std::string& where, const char* data, std::size_t size);

}  // namespace driveid
