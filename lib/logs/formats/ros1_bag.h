// ROS 1 bags, format 2.0 (docs/formats.md#ros-bags), read from the
// published format: the line "#ROSBAG V2.0", then records, each a header
// (length-prefixed "name=value" fields, `op` the record type) and data.
// Connection records (op 7) name the topic and type; message data records
// (op 2) hold a connection id, the receive time and the message in ROS
// serialisation; chunks (op 5) hold both, compressed with bz2 (libbz2) or
// lz4 (liblz4 frames) or not; index records are skipped. Every length is
// checked against the record and the file; a chunk's claimed size (at most
// 1 GiB) against what it inflates to.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "logs/formats/ros_bag.h"

namespace driveid {

/// True when `text` starts with "#ROSBAG V2.0".
bool LooksLikeRos1Bag(std::string_view text);

/// Reads a ROS 1 bag record by record: its connections as topics
/// (serialization "ros1") with their message counts, and the messages of the
/// sensor_msgs/JointState topics `sinks` takes, in the file's order.
std::vector<RosTopic> ReadRos1Bag(ByteSource& bytes, const JointStateSinks& sinks);

/// Decodes a ROS-serialised sensor_msgs/JointState into `into`; MessageError.
void DecodeJointStateRos1(const char* data, std::size_t size, JointStateMessage& into);
/// The same, throwing InputError "where: why".
JointStateMessage DecodeJointStateRos1(const std::string& where, const char* data, std::size_t size);

}  // namespace driveid
