#include "logs/formats/ros1_bag.h"

#include <bzlib.h>
#include <cstdint>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <string_view>

#include <fmt/format.h>

#include "core/errors.h"
#include "system/byte_source.h"
#include "logs/formats/joint_state_rows.h"
#include "logs/formats/ros_source.h"

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "ROS 1 bags are read as little-endian");

namespace driveid {
namespace {

const std::string kVersionLine = "#ROSBAG V2.0\n";
constexpr std::uint32_t kMaxChunkBytes = 1U << 30;
constexpr const char* kJointStateType = "sensor_msgs/JointState";

std::uint32_t U32(std::string_view s, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, s.data() + at, 4);
  return v;
}

// A record's header fields, name -> value.
std::map<std::string, std::string_view> HeaderFields(const std::string& path, std::string_view header, std::size_t offset) {
  std::map<std::string, std::string_view> fields;
  std::size_t at = 0;
  while (at < header.size()) {
    if (header.size() - at < 4) throw InputError(fmt::format("{}: ROS bag record at offset {}: a header field is cut short", path, offset));
    const std::uint32_t length = U32(header, at);
    at += 4;
    if (length > header.size() - at) {
      throw InputError(fmt::format("{}: ROS bag record at offset {}: a header field claims {} bytes, {} remain", path,
                                   offset, length, header.size() - at));
    }
    const std::string_view field = header.substr(at, length);
    at += length;
    const std::size_t eq = field.find('=');
    if (eq == std::string_view::npos) throw InputError(fmt::format("{}: ROS bag record at offset {}: a header field without '='", path, offset));
    fields[std::string(field.substr(0, eq))] = field.substr(eq + 1);
  }
  return fields;
}

std::string_view Field(const std::string& path, const std::map<std::string, std::string_view>& fields, const char* name,
                       std::size_t size, std::size_t offset) {
  const auto found = fields.find(name);
  if (found == fields.end() || (size > 0 && found->second.size() != size)) {
    throw InputError(fmt::format("{}: ROS bag record at offset {}: no {}-byte field '{}'", path, offset, size, name));
  }
  return found->second;
}

struct Connection {
  std::string topic, type;
};

struct Visitor {
  std::function<void(std::uint32_t, const Connection&)> connection;
  std::function<void(std::uint32_t, std::int64_t, std::string_view, std::size_t)> message;  // conn, time ns, data, offset
};

// Inflates a chunk into `out` (its storage reused).
void Inflate(const std::string& path, std::size_t offset, std::string_view compression, std::string_view data,
             std::uint32_t size, std::string& out) {
  if (size > kMaxChunkBytes) {
    throw InputError(fmt::format("{}: ROS bag chunk at offset {} claims {} bytes: at most {}", path, offset, size, kMaxChunkBytes));
  }
  if (compression == "none") {
    out.assign(data);
  } else if (compression == "bz2") {
    out.resize(size);
    unsigned int got = size;
    const int status = BZ2_bzBuffToBuffDecompress(out.data(), &got, const_cast<char*>(data.data()),
                                                  static_cast<unsigned int>(data.size()), 0, 0);
    if (status != BZ_OK) throw InputError(fmt::format("{}: ROS bag chunk at offset {}: bz2 error {}", path, offset, status));
    out.resize(got);
  } else if (compression == "lz4") {
    out.resize(size);
    const std::string error = InflateLz4Frame(data.data(), data.size(), out);
    if (!error.empty()) throw InputError(fmt::format("{}: ROS bag chunk at offset {}: lz4: {}", path, offset, error));
  } else {
    throw InputError(fmt::format("{}: ROS bag chunk at offset {}: compression '{}' (bz2, lz4 or none)", path, offset,
                                 std::string(compression.substr(0, 40))));
  }
  if (out.size() != size) {
    throw InputError(fmt::format("{}: ROS bag chunk at offset {}: {} bytes uncompressed, {} claimed", path, offset, out.size(), size));
  }
}

// One record, its header fields parsed and its data fetched (`data()`:
// called only for the records that are read).
template <typename Data>
void Record(const std::string& path, const std::map<std::string, std::string_view>& fields, const Data& data,
            std::size_t offset, bool in_chunk, const Visitor& visit, std::string& inflated);

// The records of a chunk (`base`: the chunk's offset in the file).
void Scan(const std::string& path, std::string_view region, std::size_t base, const Visitor& visit) {
  std::string unused;
  std::size_t at = 0;
  while (at < region.size()) {
    const auto need = [&](std::size_t bytes, const char* what) {
      if (bytes > region.size() - at) {
        throw InputError(fmt::format("{}: ROS bag record in the chunk at offset {}: {} claims {} bytes, {} remain", path,
                                     base, what, bytes, region.size() - at));
      }
    };
    need(4, "the header length");
    const std::uint32_t header_length = U32(region, at);
    at += 4;
    need(header_length, "the header");
    const auto fields = HeaderFields(path, region.substr(at, header_length), base);
    at += header_length;
    need(4, "the data length");
    const std::uint32_t data_length = U32(region, at);
    at += 4;
    need(data_length, "the data");
    const std::string_view data = region.substr(at, data_length);
    at += data_length;
    Record(path, fields, [&] { return data; }, base, true, visit, unused);
  }
}

template <typename Data>
void Record(const std::string& path, const std::map<std::string, std::string_view>& fields, const Data& data,
            std::size_t offset, bool in_chunk, const Visitor& visit, std::string& inflated) {
  const std::string_view op = Field(path, fields, "op", 1, offset);
  if (op[0] == 0x07) {
    const std::uint32_t conn = U32(Field(path, fields, "conn", 4, offset), 0);
    const std::string topic(Field(path, fields, "topic", 0, offset));
    const auto inner = HeaderFields(path, data(), offset);
    const auto type = inner.find("type");
    visit.connection(conn, {topic, type != inner.end() ? std::string(type->second) : std::string()});
  } else if (op[0] == 0x02) {
    const std::uint32_t conn = U32(Field(path, fields, "conn", 4, offset), 0);
    const std::string_view time = Field(path, fields, "time", 8, offset);
    const std::int64_t ns = static_cast<std::int64_t>(U32(time, 0)) * 1'000'000'000 + U32(time, 4);
    visit.message(conn, ns, data(), offset);
  } else if (op[0] == 0x05 && !in_chunk) {
    const std::string compression(Field(path, fields, "compression", 0, offset));
    const std::uint32_t size = U32(Field(path, fields, "size", 4, offset), 0);
    Inflate(path, offset, compression, data(), size, inflated);
    Scan(path, inflated, offset, visit);
  }
}

// The file's records one by one: the data of index records and the bag
// header's padding is skipped, not fetched.
void ScanSource(ByteSource& bytes, const Visitor& visit) {
  const std::string& path = bytes.name();
  std::string inflated, header;
  std::uint64_t at = kVersionLine.size();
  while (at < bytes.size()) {
    const std::uint64_t offset = at;
    const auto need = [&](std::uint64_t n, const char* what) {
      if (n > bytes.size() - at) {
        throw InputError(fmt::format("{}: ROS bag record at offset {}: {} claims {} bytes, {} remain", path, offset,
                                     what, n, bytes.size() - at));
      }
    };
    need(4, "the header length");
    const std::uint32_t header_length = U32(bytes.View(at, 4), 0);
    at += 4;
    need(header_length, "the header");
    header.assign(bytes.View(at, header_length));  // kept while the data is fetched
    const auto fields = HeaderFields(path, header, offset);
    at += header_length;
    need(4, "the data length");
    const std::uint32_t data_length = U32(bytes.View(at, 4), 0);
    at += 4;
    need(data_length, "the data");
    const std::uint64_t data_at = at;
    at += data_length;
    Record(path, fields, [&] { return bytes.View(data_at, data_length); }, offset, false, visit, inflated);
  }
}

// ROS serialisation, read within the message.
class Ros1Reader {
 public:
  Ros1Reader(const char* data, std::size_t size) : data_(data), size_(size) {}
  std::uint32_t U32() {
    Need(4, "a 32-bit number");
    std::uint32_t v = 0;
    std::memcpy(&v, data_ + at_, 4);
    at_ += 4;
    return v;
  }
  double Double() {
    Need(8, "a float64");
    double v = 0.0;
    std::memcpy(&v, data_ + at_, 8);
    at_ += 8;
    return v;
  }
  void String(std::string& into) {
    const std::uint32_t n = U32();
    Need(n, "a string");
    into.assign(data_ + at_, n);
    at_ += n;
  }
  void Skip() {
    const std::uint32_t n = U32();
    Need(n, "a string");
    at_ += n;
  }
  std::uint32_t Count(std::size_t least, const char* field) {
    const std::uint32_t n = U32();
    if (static_cast<std::uint64_t>(n) * least > size_ - at_) {
      throw MessageError(fmt::format("{} claims {} elements, {} bytes remain", field, n, size_ - at_));
    }
    return n;
  }

 private:
  void Need(std::size_t n, const char* what) const {
    if (n > size_ - at_) throw MessageError(fmt::format("{} claims {} bytes, {} remain: not a sensor_msgs/JointState", what, n, size_ - at_));
  }
  const char* data_;
  std::size_t size_, at_ = 0;
};

}  // namespace

bool LooksLikeRos1Bag(std::string_view text) { return text.compare(0, kVersionLine.size(), kVersionLine) == 0; }

void DecodeJointStateRos1(const char* data, std::size_t size, JointStateMessage& m) {
  Ros1Reader r(data, size);
  r.U32();  // seq
  const std::uint32_t sec = r.U32(), nsec = r.U32();
  if (nsec >= 1'000'000'000U) throw MessageError(fmt::format("header.stamp.nsec = {}", nsec));
  m.stamp_ns = static_cast<std::int64_t>(sec) * 1'000'000'000 + nsec;
  r.Skip();  // frame_id
  m.name.resize(r.Count(4, "name[]"));
  for (auto& n : m.name) r.String(n);
  for (auto* values : {&m.position, &m.velocity, &m.effort}) {
    values->resize(r.Count(8, values == &m.position ? "position[]" : values == &m.velocity ? "velocity[]" : "effort[]"));
    for (double& v : *values) v = r.Double();
  }
}

JointStateMessage DecodeJointStateRos1(const std::string& where, const char* data, std::size_t size) {
  JointStateMessage m;
  try {
    DecodeJointStateRos1(data, size, m);
  } catch (const MessageError& e) {
    throw InputError(fmt::format("{}: {}", where, e.what()));
  }
  return m;
}

std::vector<RosTopic> ReadRos1Bag(ByteSource& bytes, const JointStateSinks& sinks) {
  const std::string& path = bytes.name();
  if (bytes.size() < kVersionLine.size() || bytes.View(0, kVersionLine.size()) != kVersionLine) {
    throw InputError(fmt::format("{}: not a ROS 1 bag (no #ROSBAG V2.0 line)", path));
  }
  std::map<std::uint32_t, Connection> connections;
  std::map<std::string, RosTopic> counts;
  std::map<std::string, std::pair<JointStateRows*, std::size_t>> sinks_met;  // topic: sink, messages decoded
  JointStateMessage message;
  Visitor visit;
  visit.connection = [&](std::uint32_t id, const Connection& c) { connections[id] = c; };
  visit.message = [&](std::uint32_t id, std::int64_t ns, std::string_view data, std::size_t offset) {
    const auto found = connections.find(id);
    if (found == connections.end()) {
      throw InputError(fmt::format("{}: ROS bag message at offset {} on connection {}, which no connection record defined",
                                   path, offset, id));
    }
    const Connection& c = found->second;
    RosTopic& t = counts[c.topic];
    if (t.messages == 0) t.first_ns = t.last_ns = ns;
    t.first_ns = std::min(t.first_ns, ns);
    t.last_ns = std::max(t.last_ns, ns);
    ++t.messages;
    if (c.type != kJointStateType) return;
    auto sink = sinks_met.find(c.topic);
    if (sink == sinks_met.end()) sink = sinks_met.emplace(c.topic, std::pair{sinks(c.topic), std::size_t{0}}).first;
    if (sink->second.first == nullptr) return;
    const std::size_t index = ++sink->second.second;
    try {
      DecodeJointStateRos1(data.data(), data.size(), message);
    } catch (const MessageError& e) {
      throw InputError(fmt::format("{}: {} message {} (record at offset {}): {}", path, c.topic, index, offset, e.what()));
    }
    message.receive_ns = ns;
    sink->second.first->Add(message);
  };
  ScanSource(bytes, visit);
  bytes.CheckUnchanged();
  std::vector<RosTopic> out;
  std::map<std::string, bool> seen;
  for (const auto& [id, c] : connections) {
    if (seen[c.topic]) continue;  // several connections (publishers) on one topic
    seen[c.topic] = true;
    RosTopic t = counts[c.topic];
    t.name = c.topic;
    t.type = c.type == kJointStateType ? "sensor_msgs/msg/JointState" : c.type;
    t.serialization = "ros1";
    out.push_back(t);
  }
  return out;
}

// A ROS 1 bag (format 2.0).
DRIVEID_LOG_FORMAT(ros1_bag) { return BagLogFormat("ros1", LooksLikeRos1Bag, {"ROS 1 (2.0)", ReadRos1Bag, {}}); }

}  // namespace driveid
