#include "logs/formats/mcap.h"

#include <cstdint>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <string_view>

#include <fmt/format.h>
#include <zlib.h>
#include <zstd.h>

#include "core/errors.h"
#include "system/byte_source.h"
#include "logs/formats/joint_state_rows.h"
#include "logs/formats/ros_source.h"

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "MCAP is read as little-endian");

namespace driveid {
namespace {

const std::string kMagic("\x89MCAP0\r\n", 8);
constexpr const char* kJointStateType = "sensor_msgs/msg/JointState";
constexpr std::uint64_t kMaxChunkBytes = std::uint64_t{1} << 30;  // one chunk, uncompressed

enum Opcode : unsigned char { kSchema = 0x03, kChannel = 0x04, kMessage = 0x05, kChunk = 0x06, kDataEnd = 0x0F, kFooter = 0x02 };

// Fields of one record, each read within it.
class Fields {
 public:
  Fields(const std::string& path, std::string_view content, std::size_t offset)
      : path_(path), content_(content), offset_(offset) {}
  template <typename T>
  T Number(const char* what) {
    Need(sizeof(T), what);
    T value{};
    std::memcpy(&value, content_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  std::string_view Bytes(std::uint64_t length, const char* what) {
    Need(length, what);
    const std::string_view out = content_.substr(at_, length);
    at_ += length;
    return out;
  }
  std::string Text(const char* what) { return std::string(Bytes(Number<std::uint32_t>(what), what)); }
  std::string_view Rest() const { return content_.substr(at_); }

 private:
  void Need(std::uint64_t bytes, const char* what) const {
    if (bytes > content_.size() - at_) {
      throw InputError(fmt::format("{}: MCAP record at offset {}: {} claims {} bytes, {} remain in the record", path_,
                                   offset_, what, bytes, content_.size() - at_));
    }
  }
  const std::string& path_;
  std::string_view content_;
  std::size_t offset_;
  std::size_t at_ = 0;
};

struct Channel {
  std::string topic, encoding;
  std::uint16_t schema_id = 0;
};

struct Visitor {
  std::function<void(std::uint16_t, const std::string&)> schema;  // id, name
  std::function<void(std::uint16_t, const Channel&)> channel;
  std::function<void(std::uint16_t, std::uint64_t, std::string_view, std::size_t)> message;  // channel, log time, data, offset
};

// Inflates a chunk's records into `out` (its storage reused).
void Inflate(const std::string& path, std::size_t offset, const std::string& compression, std::string_view data,
             std::uint64_t size, std::uint32_t crc, std::string& out) {
  if (size > kMaxChunkBytes) {
    throw InputError(fmt::format("{}: MCAP chunk at offset {} claims {} bytes uncompressed: at most {}", path, offset,
                                 size, kMaxChunkBytes));
  }
  if (compression.empty()) {
    out.assign(data);
  } else if (compression == "zstd") {
    out.resize(size);
    const std::size_t got = ZSTD_decompress(out.data(), out.size(), data.data(), data.size());
    if (ZSTD_isError(got)) {
      throw InputError(fmt::format("{}: MCAP chunk at offset {}: zstd: {}", path, offset, ZSTD_getErrorName(got)));
    }
    out.resize(got);
  } else if (compression == "lz4") {
    out.resize(size);
    const std::string error = InflateLz4Frame(data.data(), data.size(), out);
    if (!error.empty()) throw InputError(fmt::format("{}: MCAP chunk at offset {}: lz4: {}", path, offset, error));
  } else {
    throw InputError(fmt::format("{}: MCAP chunk at offset {}: compression '{}' (this reader knows zstd, lz4 and none)",
                                 path, offset, compression.substr(0, 40)));
  }
  if (out.size() != size) {
    throw InputError(fmt::format("{}: MCAP chunk at offset {}: {} bytes uncompressed, {} claimed", path, offset, out.size(), size));
  }
  if (crc != 0 && crc32(0L, reinterpret_cast<const Bytef*>(out.data()), static_cast<uInt>(out.size())) != crc) {
    throw InputError(fmt::format("{}: MCAP chunk at offset {}: CRC-32 mismatch (a corrupt chunk)", path, offset));
  }
}

void Scan(const std::string& path, std::string_view region, std::size_t base, const Visitor& visit);

// One record (`content`: its bytes after the opcode and length); false at
// the end of the data section (the summary that follows holds indexes only).
bool Record(const std::string& path, unsigned char opcode, std::string_view content, std::size_t offset, bool in_chunk,
            const Visitor& visit, std::string& inflated) {
  Fields f(path, content, offset);
  if (opcode == kChannel) {
    Channel c;
    const auto id = f.Number<std::uint16_t>("the channel id");
    c.schema_id = f.Number<std::uint16_t>("the schema id");
    c.topic = f.Text("the topic");
    c.encoding = f.Text("the message encoding");
    visit.channel(id, c);
  } else if (opcode == kSchema) {
    const auto id = f.Number<std::uint16_t>("the schema id");
    visit.schema(id, f.Text("the schema name"));
  } else if (opcode == kMessage) {
    const auto channel = f.Number<std::uint16_t>("the channel id");
    f.Number<std::uint32_t>("the sequence");
    const auto log_time = f.Number<std::uint64_t>("the log time");
    f.Number<std::uint64_t>("the publish time");
    visit.message(channel, log_time, f.Rest(), offset);
  } else if (opcode == kChunk && !in_chunk) {
    f.Number<std::uint64_t>("the start time");
    f.Number<std::uint64_t>("the end time");
    const auto size = f.Number<std::uint64_t>("the uncompressed size");
    const auto crc = f.Number<std::uint32_t>("the CRC");
    const std::string compression = f.Text("the compression");
    const std::string_view records = f.Bytes(f.Number<std::uint64_t>("the records' length"), "the records");
    Inflate(path, offset, compression, records, size, crc, inflated);
    Scan(path, inflated, offset, visit);
  } else if ((opcode == kDataEnd || opcode == kFooter) && !in_chunk) {
    return false;
  }
  return true;
}

// The records of a chunk (`base`: the chunk's offset in the file).
void Scan(const std::string& path, std::string_view region, std::size_t base, const Visitor& visit) {
  std::string unused;
  std::size_t at = 0;
  while (at < region.size()) {
    if (region.size() - at < 9) {
      throw InputError(fmt::format("{}: MCAP record in the chunk at offset {} is cut short ({} bytes)", path, base,
                                   region.size() - at));
    }
    std::uint64_t length = 0;
    std::memcpy(&length, region.data() + at + 1, 8);
    if (length > region.size() - at - 9) {
      throw InputError(fmt::format("{}: MCAP record in the chunk at offset {} claims {} bytes, {} remain", path, base,
                                   length, region.size() - at - 9));
    }
    Record(path, static_cast<unsigned char>(region[at]), region.substr(at + 9, length), base, true, visit, unused);
    at += 9 + length;
  }
}

// The file's records, read one by one: only the records read (channels,
// schemas, messages, chunks) are fetched, the rest (attachments, indexes)
// skipped by their length.
void ScanSource(ByteSource& bytes, const Visitor& visit) {
  const std::string& path = bytes.name();
  std::string inflated;
  std::uint64_t at = kMagic.size();
  while (at < bytes.size()) {
    if (bytes.size() - at < 9) {
      throw InputError(fmt::format("{}: MCAP record at offset {} is cut short ({} bytes)", path, at, bytes.size() - at));
    }
    const std::string_view head = bytes.View(at, 9);
    const auto opcode = static_cast<unsigned char>(head[0]);
    std::uint64_t length = 0;
    std::memcpy(&length, head.data() + 1, 8);
    if (length > bytes.size() - at - 9) {
      throw InputError(fmt::format("{}: MCAP record at offset {} claims {} bytes, {} remain", path, at, length,
                                   bytes.size() - at - 9));
    }
    if (opcode == kChannel || opcode == kSchema || opcode == kMessage || opcode == kChunk || opcode == kDataEnd ||
        opcode == kFooter) {
      if (!Record(path, opcode, bytes.View(at + 9, length), at, false, visit, inflated)) return;
    }
    at += 9 + length;
  }
}

}  // namespace

bool LooksLikeMcap(std::string_view text) { return text.compare(0, kMagic.size(), kMagic) == 0; }

bool McapComplete(ByteSource& bytes) {
  return bytes.size() >= 2 * kMagic.size() && bytes.View(bytes.size() - kMagic.size(), kMagic.size()) == kMagic;
}

std::vector<RosTopic> ReadMcapBag(ByteSource& bytes, const JointStateSinks& sinks) {
  const std::string& path = bytes.name();
  if (bytes.size() < kMagic.size() || bytes.View(0, kMagic.size()) != kMagic) {
    throw InputError(fmt::format("{}: not an MCAP file", path));
  }
  std::map<std::uint16_t, Channel> channels;
  std::map<std::uint16_t, std::string> schemas;
  std::map<std::string, RosTopic> counts;
  // Per channel: its topic's counts and sink, set when its first message comes.
  struct Route {
    RosTopic* topic = nullptr;
    JointStateRows* sink = nullptr;
    std::size_t* decoded = nullptr;
  };
  std::map<std::uint16_t, Route> routes;
  std::map<std::string, std::size_t> decoded;
  JointStateMessage message;
  Visitor visit;
  visit.schema = [&](std::uint16_t id, const std::string& name) { schemas[id] = name; };
  visit.channel = [&](std::uint16_t id, const Channel& c) {
    channels[id] = c;
    routes.erase(id);
  };
  visit.message = [&](std::uint16_t id, std::uint64_t log_time, std::string_view data, std::size_t offset) {
    auto route = routes.find(id);
    if (route == routes.end()) {
      const auto found = channels.find(id);
      if (found == channels.end()) {
        throw InputError(fmt::format("{}: MCAP message at offset {} on channel {}, which no Channel record defined",
                                     path, offset, id));
      }
      const auto schema = schemas.find(found->second.schema_id);
      Route r{&counts[found->second.topic], nullptr, &decoded[found->second.topic]};
      if (schema != schemas.end() && schema->second == kJointStateType && found->second.encoding == "cdr") {
        r.sink = sinks(found->second.topic);
      }
      route = routes.emplace(id, r).first;
    }
    RosTopic& topic = *route->second.topic;
    const auto ns = static_cast<std::int64_t>(log_time);
    if (topic.messages == 0) topic.first_ns = topic.last_ns = ns;
    topic.first_ns = std::min(topic.first_ns, ns);
    topic.last_ns = std::max(topic.last_ns, ns);
    ++topic.messages;
    if (route->second.sink == nullptr) return;
    const std::size_t index = ++*route->second.decoded;
    try {
      DecodeJointStateCdr(data.data(), data.size(), message);
    } catch (const MessageError& e) {
      throw InputError(fmt::format("{}: {} message {} (MCAP record at offset {}): {}", path, channels[id].topic, index,
                                   offset, e.what()));
    }
    message.receive_ns = ns;
    route->second.sink->Add(message);
  };
  ScanSource(bytes, visit);
  bytes.CheckUnchanged();
  std::vector<RosTopic> out;
  std::map<std::string, bool> listed;
  for (const auto& [id, c] : channels) {
    if (listed[c.topic]) continue;
    listed[c.topic] = true;
    RosTopic t = counts[c.topic];
    t.name = c.topic;
    const auto schema = schemas.find(c.schema_id);
    t.type = schema != schemas.end() ? schema->second : "";
    t.serialization = c.encoding;
    out.push_back(t);
  }
  return out;
}

// A rosbag2 MCAP file; one cut while it was written is read up to the cut, and said.
DRIVEID_LOG_FORMAT(mcap) {
  const auto notes = [](ByteSource& bytes) {
    std::vector<std::string> out;
    if (!McapComplete(bytes)) {
      out.push_back(fmt::format("{} the MCAP file ends without its closing magic: cut while it was written? "
                                "(its records up to the cut are read)",
                                kReaderWarning));
    }
    return out;
  };
  return BagLogFormat("rosbag2-mcap", LooksLikeMcap, {"rosbag2 MCAP", ReadMcapBag, notes});
}

}  // namespace driveid
