// MCAP (docs/formats.md#ros-bags), the default rosbag2 storage since Iron,
// read from its published specification: the magic "\x89MCAP0\r\n", then
// records (an opcode byte, a 64-bit length, the content), little-endian.
// Schema, Channel and Message records are read, in the data section and
// inside Chunks (compressed with zstd or lz4 frames, or not at all; the
// uncompressed size and CRC-32 the chunk claims are checked); index and
// summary records are skipped. Every length is checked against the record
// it lies in and the file; what is corrupt is refused with its offset.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "logs/formats/ros_bag.h"

namespace driveid {

/// True when `text` starts with the MCAP magic.
bool LooksLikeMcap(std::string_view text);

/// True when the file ends with the closing magic (a recorder that was
/// stopped, not killed, wrote it).
bool McapComplete(ByteSource& bytes);

/// Reads an MCAP file record by record: its channels as topics (type: the
/// schema's name, serialization: the channel's message encoding) with their
/// message counts, and the messages of the JointState topics (CDR) `sinks`
/// takes, in the file's order.
std::vector<RosTopic> ReadMcapBag(ByteSource& bytes, const JointStateSinks& sinks);

}  // namespace driveid
