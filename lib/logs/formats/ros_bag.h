// ROS bags (docs/formats.md#ros-bags): a rosbag2 SQLite3 file (`.db3`, or
// its folder with metadata.yaml), read with libsqlite3, and
// `sensor_msgs/msg/JointState` messages decoded from CDR with libfastcdr.
// Every sequence length a message claims is checked against the bytes it
// has left before anything is allocated; a message that does not decode is
// refused with its topic, index and receive time.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "logs/formats/joint_state_message.h"

namespace driveid {

class ByteSource;

/// True when `text` is an SQLite 3 database (a rosbag2 .db3).
bool LooksLikeSqlite(std::string_view text);

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
