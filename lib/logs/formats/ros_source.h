// A ROS bag's JointState topic as a table (docs/formats.md#ros-bags), for
// every bag container alike: the container's reader (rosbag2 SQLite3,
// rosbag2 MCAP, ROS 1) hands each JointState message to the rows its topic
// keeps, and this makes the table, or with LogSelection::catalog the list of
// topics. Each container registers itself through BagLogFormat.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "logs/formats/joint_state_message.h"
#include "logs/log_format.h"
#include "logs/table_source.h"

namespace driveid {

class ByteSource;

/// A bag container: its name in `inspect` ("rosbag2 MCAP"), its reader and
/// what it says of the file as a whole (a cut MCAP), else nullptr.
struct BagContainer {
  std::string label;
  std::function<std::vector<RosTopic>(ByteSource& bytes, const JointStateSinks& sinks)> read;
  std::function<std::vector<std::string>(ByteSource& bytes)> file_notes;
};

/// The nearest double to `ns` nanoseconds in seconds (a bag's stamps read
/// as a CSV's decimal text of them is: bit-equal).
double NearestSeconds(std::int64_t ns);

/// The bag's JointState topic (the one of LogSelection::topic, or the only
/// one), or with catalog its topics then that topic when one can be chosen.
/// Read from LogSelection::stream_file when given, else from `text`.
std::vector<std::unique_ptr<TableSource>> OpenRosBagSources(const std::string& path, const std::string& text,
                                                            const LogSelection& format, const BagContainer& container);

/// The registration of a bag container: the bags' options, catalog and
/// streaming, its `name`, how it is told from its first bytes, its reader.
LogFormat BagLogFormat(std::string name, std::function<bool(std::string_view head)> sniff, BagContainer container);

}  // namespace driveid
