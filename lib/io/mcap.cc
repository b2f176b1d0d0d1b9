#include "io/mcap.h"

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

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "MCAP is read as little-endian");

namespace driveid {
namespace {

const std::string kMagic("\x89MCAP0\r\n", 8);
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

std::string Inflate(const std::string& path, std::size_t offset, const std::string& compression, std::string_view data,
                    std::uint64_t size, std::uint32_t crc) {
  if (size > kMaxChunkBytes) {
    throw InputError(fmt::format("{}: MCAP chunk at offset {} claims {} bytes uncompressed: at most {}", path, offset,
                                 size, kMaxChunkBytes));
  }
  std::string out;
  if (compression.empty()) {
    out = std::string(data);
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
  return out;
}

// Reads the records of `region` (the file's data section or a chunk's
// records; `base`: its offset in the file, for messages).
void Scan(const std::string& path, std::string_view region, std::size_t base, bool in_chunk, const Visitor& visit) {
  std::size_t at = 0;
  while (at < region.size()) {
    const std::size_t offset = base + at;
    if (region.size() - at < 9) {
      throw InputError(fmt::format("{}: MCAP record at offset {} is cut short ({} bytes)", path, offset, region.size() - at));
    }
    const auto opcode = static_cast<unsigned char>(region[at]);
    std::uint64_t length = 0;
    std::memcpy(&length, region.data() + at + 1, 8);
    if (length > region.size() - at - 9) {
      throw InputError(fmt::format("{}: MCAP record at offset {} claims {} bytes, {} remain", path, offset, length,
                                   region.size() - at - 9));
    }
    Fields f(path, region.substr(at + 9, length), offset);
    at += 9 + length;
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
      const std::string inner = Inflate(path, offset, compression, records, size, crc);
      Scan(path, inner, offset, true, visit);
    } else if ((opcode == kDataEnd || opcode == kFooter) && !in_chunk) {
      return;  // the summary section follows: indexes only
    }
  }
}

}  // namespace

bool LooksLikeMcap(const std::string& text) { return text.compare(0, kMagic.size(), kMagic) == 0; }

bool McapComplete(const std::string& text) {
  return text.size() >= 2 * kMagic.size() && text.compare(text.size() - kMagic.size(), kMagic.size(), kMagic) == 0;
}

namespace {

// Channels with their schema names, and per channel the messages counted.
struct McapCatalog {
  std::map<std::uint16_t, Channel> channels;
  std::map<std::uint16_t, std::string> schemas;
};

void ScanFile(const std::string& path, const std::string& bytes, McapCatalog& catalog,
              const std::function<void(const Channel&, std::uint64_t, std::string_view, std::size_t)>& message) {
  if (!LooksLikeMcap(bytes)) throw InputError(fmt::format("{}: not an MCAP file", path));
  Visitor visit;
  visit.schema = [&](std::uint16_t id, const std::string& name) { catalog.schemas[id] = name; };
  visit.channel = [&](std::uint16_t id, const Channel& c) { catalog.channels[id] = c; };
  visit.message = [&](std::uint16_t id, std::uint64_t log_time, std::string_view data, std::size_t offset) {
    const auto found = catalog.channels.find(id);
    if (found == catalog.channels.end()) {
      throw InputError(fmt::format("{}: MCAP message at offset {} on channel {}, which no Channel record defined", path,
                                   offset, id));
    }
    if (message) message(found->second, log_time, data, offset);
  };
  Scan(path, std::string_view(bytes).substr(kMagic.size()), kMagic.size(), false, visit);
}

}  // namespace

std::vector<RosTopic> ReadMcapTopics(const std::string& path, const std::string& bytes) {
  McapCatalog catalog;
  std::map<std::string, RosTopic> topics;
  std::vector<std::string> order;
  ScanFile(path, bytes, catalog, [&](const Channel& c, std::uint64_t t, std::string_view, std::size_t) {
    RosTopic& topic = topics[c.topic];
    const auto ns = static_cast<std::int64_t>(t);
    if (topic.messages == 0) topic.first_ns = ns;
    topic.first_ns = std::min(topic.first_ns, ns);
    topic.last_ns = std::max(topic.last_ns, ns);
    ++topic.messages;
  });
  std::vector<RosTopic> out;
  for (const auto& [id, c] : catalog.channels) {
    RosTopic t = topics[c.topic];
    t.name = c.topic;
    const auto schema = catalog.schemas.find(c.schema_id);
    t.type = schema != catalog.schemas.end() ? schema->second : "";
    t.serialization = c.encoding;
    out.push_back(t);
  }
  return out;
}

std::vector<JointStateMessage> ReadMcapJointStates(const std::string& path, const std::string& bytes,
                                                   const std::string& topic) {
  McapCatalog catalog;
  std::vector<JointStateMessage> out;
  ScanFile(path, bytes, catalog, [&](const Channel& c, std::uint64_t t, std::string_view data, std::size_t offset) {
    if (c.topic != topic) return;
    if (c.encoding != "cdr") throw InputError(fmt::format("{}: topic {} is encoded {}, not CDR", path, topic, c.encoding));
    const std::string where = fmt::format("{}: {} message {} (MCAP record at offset {})", path, topic, out.size() + 1, offset);
    JointStateMessage m = DecodeJointStateCdr(where, data.data(), data.size());
    m.receive_ns = static_cast<std::int64_t>(t);
    out.push_back(std::move(m));
  });
  return out;
}

}  // namespace driveid
