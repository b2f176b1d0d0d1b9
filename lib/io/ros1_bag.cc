#include "io/ros1_bag.h"

#include <bzlib.h>
#include <cstdint>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <string_view>

#include <fmt/format.h>

#include "core/errors.h"

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

std::string Inflate(const std::string& path, std::size_t offset, std::string_view compression, std::string_view data,
                    std::uint32_t size) {
  if (size > kMaxChunkBytes) {
    throw InputError(fmt::format("{}: ROS bag chunk at offset {} claims {} bytes: at most {}", path, offset, size, kMaxChunkBytes));
  }
  std::string out;
  if (compression == "none") {
    out = std::string(data);
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
  return out;
}

void Scan(const std::string& path, std::string_view region, std::size_t base, bool in_chunk, const Visitor& visit) {
  std::size_t at = 0;
  while (at < region.size()) {
    const std::size_t offset = base + at;
    const auto need = [&](std::size_t bytes, const char* what) {
      if (bytes > region.size() - at) {
        throw InputError(fmt::format("{}: ROS bag record at offset {}: {} claims {} bytes, {} remain", path, offset, what,
                                     bytes, region.size() - at));
      }
    };
    need(4, "the header length");
    const std::uint32_t header_length = U32(region, at);
    at += 4;
    need(header_length, "the header");
    const auto fields = HeaderFields(path, region.substr(at, header_length), offset);
    at += header_length;
    need(4, "the data length");
    const std::uint32_t data_length = U32(region, at);
    at += 4;
    need(data_length, "the data");
    const std::string_view data = region.substr(at, data_length);
    at += data_length;
    const std::string_view op = Field(path, fields, "op", 1, offset);
    if (op[0] == 0x07) {
      const std::uint32_t conn = U32(Field(path, fields, "conn", 4, offset), 0);
      const auto inner = HeaderFields(path, data, offset);
      const auto type = inner.find("type");
      visit.connection(conn, {std::string(Field(path, fields, "topic", 0, offset)),
                              type != inner.end() ? std::string(type->second) : std::string()});
    } else if (op[0] == 0x02) {
      const std::uint32_t conn = U32(Field(path, fields, "conn", 4, offset), 0);
      const std::string_view time = Field(path, fields, "time", 8, offset);
      const std::int64_t ns = static_cast<std::int64_t>(U32(time, 0)) * 1'000'000'000 + U32(time, 4);
      visit.message(conn, ns, data, offset);
    } else if (op[0] == 0x05 && !in_chunk) {
      const std::string inner = Inflate(path, offset, Field(path, fields, "compression", 0, offset), data,
                                        U32(Field(path, fields, "size", 4, offset), 0));
      Scan(path, inner, offset, true, visit);
    }
  }
}

void ScanFile(const std::string& path, const std::string& bytes, std::map<std::uint32_t, Connection>& connections,
              const std::function<void(const Connection&, std::int64_t, std::string_view, std::size_t)>& message) {
  if (!LooksLikeRos1Bag(bytes)) throw InputError(fmt::format("{}: not a ROS 1 bag (no #ROSBAG V2.0 line)", path));
  Visitor visit;
  visit.connection = [&](std::uint32_t id, const Connection& c) { connections[id] = c; };
  visit.message = [&](std::uint32_t id, std::int64_t ns, std::string_view data, std::size_t offset) {
    const auto found = connections.find(id);
    if (found == connections.end()) {
      throw InputError(fmt::format("{}: ROS bag message at offset {} on connection {}, which no connection record defined",
                                   path, offset, id));
    }
    message(found->second, ns, data, offset);
  };
  Scan(path, std::string_view(bytes).substr(kVersionLine.size()), kVersionLine.size(), false, visit);
}

// ROS serialisation, read within the message.
class Ros1Reader {
 public:
  Ros1Reader(const std::string& where, const char* data, std::size_t size) : where_(where), data_(data), size_(size) {}
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
  std::string String() {
    const std::uint32_t n = U32();
    Need(n, "a string");
    std::string s(data_ + at_, n);
    at_ += n;
    return s;
  }
  std::uint32_t Count(std::size_t least, const char* field) {
    const std::uint32_t n = U32();
    if (static_cast<std::uint64_t>(n) * least > size_ - at_) {
      throw InputError(fmt::format("{}: {} claims {} elements, {} bytes remain", where_, field, n, size_ - at_));
    }
    return n;
  }

 private:
  void Need(std::size_t n, const char* what) const {
    if (n > size_ - at_) throw InputError(fmt::format("{}: {} claims {} bytes, {} remain: not a sensor_msgs/JointState", where_, what, n, size_ - at_));
  }
  const std::string& where_;
  const char* data_;
  std::size_t size_, at_ = 0;
};

}  // namespace

bool LooksLikeRos1Bag(const std::string& text) { return text.compare(0, kVersionLine.size(), kVersionLine) == 0; }

JointStateMessage DecodeJointStateRos1(const std::string& where, const char* data, std::size_t size) {
  Ros1Reader r(where, data, size);
  JointStateMessage m;
  r.U32();  // seq
  const std::uint32_t sec = r.U32(), nsec = r.U32();
  if (nsec >= 1'000'000'000U) throw InputError(fmt::format("{}: header.stamp.nsec = {}", where, nsec));
  m.stamp_ns = static_cast<std::int64_t>(sec) * 1'000'000'000 + nsec;
  r.String();  // frame_id
  m.name.resize(r.Count(4, "name[]"));
  for (auto& n : m.name) n = r.String();
  for (auto* values : {&m.position, &m.velocity, &m.effort}) {
    values->resize(r.Count(8, values == &m.position ? "position[]" : values == &m.velocity ? "velocity[]" : "effort[]"));
    for (double& v : *values) v = r.Double();
  }
  return m;
}

std::vector<RosTopic> ReadRos1Topics(const std::string& path, const std::string& bytes) {
  std::map<std::uint32_t, Connection> connections;
  std::map<std::string, RosTopic> counts;
  ScanFile(path, bytes, connections, [&](const Connection& c, std::int64_t ns, std::string_view, std::size_t) {
    RosTopic& t = counts[c.topic];
    if (t.messages == 0) t.first_ns = t.last_ns = ns;
    t.first_ns = std::min(t.first_ns, ns);
    t.last_ns = std::max(t.last_ns, ns);
    ++t.messages;
  });
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

std::vector<JointStateMessage> ReadRos1JointStates(const std::string& path, const std::string& bytes,
                                                   const std::string& topic) {
  std::map<std::uint32_t, Connection> connections;
  std::vector<JointStateMessage> out;
  ScanFile(path, bytes, connections, [&](const Connection& c, std::int64_t ns, std::string_view data, std::size_t offset) {
    if (c.topic != topic) return;
    if (c.type != kJointStateType) throw InputError(fmt::format("{}: topic {} is {}, not {}", path, topic, c.type, kJointStateType));
    const std::string where = fmt::format("{}: {} message {} (record at offset {})", path, topic, out.size() + 1, offset);
    JointStateMessage m = DecodeJointStateRos1(where, data.data(), data.size());
    m.receive_ns = ns;
    out.push_back(std::move(m));
  });
  return out;
}

}  // namespace driveid
