#include "logs/formats/wpilog.h"

#include <algorithm>
#include <cstring>
#include <map>

#include <fmt/format.h>

#include "core/errors.h"

// Payloads are little-endian; so is every host this builds for.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "WPILog payloads are read as little-endian");

namespace driveid {
namespace {

constexpr std::string_view kMagic = "WPILOG";

// `bytes` little-endian bytes at `at` as an unsigned number.
std::uint64_t Unsigned(std::string_view text, std::size_t at, int bytes) {
  std::uint64_t value = 0;
  for (int i = bytes - 1; i >= 0; --i) value = (value << 8) | static_cast<unsigned char>(text[at + static_cast<std::size_t>(i)]);
  return value;
}

// Reads the control payloads' length-prefixed strings, each checked
// against what the payload holds.
class ControlPayload {
 public:
  ControlPayload(const std::string& path, std::string_view payload, std::size_t offset)
      : path_(path), payload_(payload), offset_(offset) {}
  std::uint32_t Number() {
    Need(4, "a 32-bit number");
    const auto value = static_cast<std::uint32_t>(Unsigned(payload_, at_, 4));
    at_ += 4;
    return value;
  }
  std::string Text(const char* what) {
    const std::uint32_t length = Number();
    Need(length, what);
    std::string out(payload_.substr(at_, length));
    at_ += length;
    return out;
  }

 private:
  void Need(std::size_t bytes, const char* what) const {
    if (bytes > payload_.size() - at_) {
      throw InputError(fmt::format("{}: control record at offset {}: {} claims {} bytes, {} remain in the record",
                                   path_, offset_, what, bytes, payload_.size() - at_));
    }
  }
  const std::string& path_;
  std::string_view payload_;
  std::size_t offset_;
  std::size_t at_ = 1;  // after the control type byte
};

struct ActiveEntries {
  std::map<std::uint32_t, std::size_t> by_id;  // id -> index in entries
};

void Control(const std::string& path, const WpilogRecord& record, WpilogIndex& index, ActiveEntries& active) {
  if (record.payload.empty()) throw InputError(fmt::format("{}: control record at offset {} is empty", path, record.offset));
  ControlPayload payload(path, record.payload, record.offset);
  const auto kind = static_cast<unsigned char>(record.payload[0]);
  if (kind == 0) {
    WpilogEntry entry;
    entry.id = payload.Number();
    entry.name = payload.Text("the entry name");
    entry.type = payload.Text("the entry type");
    entry.metadata = payload.Text("the entry metadata");
    if (entry.id == 0) throw InputError(fmt::format("{}: control record at offset {} starts entry 0", path, record.offset));
    entry.start_order = index.entries.size();
    active.by_id[entry.id] = index.entries.size();  // a Start without Finish replaces the entry
    index.entries.push_back(std::move(entry));
  } else if (kind == 1) {
    active.by_id.erase(payload.Number());
  } else if (kind == 2) {
    const std::uint32_t id = payload.Number();
    std::string metadata = payload.Text("the metadata");
    const auto found = active.by_id.find(id);
    if (found != active.by_id.end()) index.entries[found->second].metadata = std::move(metadata);
  } else {
    throw InputError(fmt::format("{}: control record at offset {}: unknown control type {}", path, record.offset, kind));
  }
}

}  // namespace

bool LooksLikeWpilog(std::string_view text) { return text.substr(0, kMagic.size()) == kMagic; }

WpilogIndex ReadWpilog(const std::string& path, std::string_view text, const std::function<void(const WpilogRecord&)>& visit) {
  if (!LooksLikeWpilog(text) || text.size() < 12) throw InputError(fmt::format("{}: not a WPILib DataLog (no WPILOG header)", path));
  WpilogIndex index;
  index.version = static_cast<std::uint16_t>(Unsigned(text, 6, 2));
  if ((index.version >> 8) != 1) {
    throw InputError(fmt::format("{}: WPILog version {}.{}: this reader knows version 1.x", path, index.version >> 8,
                                 index.version & 0xff));
  }
  const std::uint64_t extra = Unsigned(text, 8, 4);
  if (extra > text.size() - 12) {
    throw InputError(fmt::format("{}: the extra header claims {} bytes, {} remain", path, extra, text.size() - 12));
  }
  index.extra_header = std::string(text.substr(12, extra));
  ActiveEntries active;
  std::size_t at = 12 + extra;
  while (at < text.size()) {
    const std::size_t start = at;
    const auto lengths = static_cast<unsigned char>(text[at++]);
    const int id_bytes = (lengths & 3) + 1, size_bytes = ((lengths >> 2) & 3) + 1, time_bytes = ((lengths >> 4) & 7) + 1;
    const std::size_t header = static_cast<std::size_t>(id_bytes + size_bytes + time_bytes);
    if (header > text.size() - at) {
      throw InputError(fmt::format("{}: record at offset {} is cut short: its header needs {} bytes, {} remain", path,
                                   start, header + 1, text.size() - start));
    }
    const auto id = static_cast<std::uint32_t>(Unsigned(text, at, id_bytes));
    const std::uint64_t size = Unsigned(text, at + id_bytes, size_bytes);
    std::uint64_t raw_time = Unsigned(text, at + id_bytes + size_bytes, time_bytes);
    at += header;
    if (size > text.size() - at) {
      throw InputError(fmt::format("{}: record at offset {} claims {} bytes of payload, {} remain in the file", path, start,
                                   size, text.size() - at));
    }
    WpilogRecord record;
    record.payload = text.substr(at, size);
    record.offset = start;
    at += size;
    ++index.records;
    const bool negative = time_bytes == 8 && (raw_time >> 63) != 0;
    std::int64_t timestamp = 0;
    std::memcpy(&timestamp, &raw_time, sizeof timestamp);
    record.timestamp_us = timestamp;
    if (id == 0) {
      Control(path, record, index, active);
      continue;
    }
    const auto found = active.by_id.find(id);
    if (found == active.by_id.end()) {
      ++index.orphan_records;
      continue;
    }
    WpilogEntry& entry = index.entries[found->second];
    if (negative) {
      ++entry.negative_records;
      continue;
    }
    if (entry.records == 0) entry.first_us = timestamp;
    entry.last_us = std::max(entry.last_us, timestamp);
    ++entry.records;
    record.entry = &entry;
    if (visit) visit(record);
  }
  return index;
}

bool WpilogNumber(const std::string& type, std::string_view payload, double& value) {
  if (type == "double" && payload.size() == 8) {
    std::memcpy(&value, payload.data(), 8);
    return true;
  }
  if (type == "float" && payload.size() == 4) {
    float f = 0.0F;
    std::memcpy(&f, payload.data(), 4);
    value = f;
    return true;
  }
  if (type == "int64" && payload.size() == 8) {
    std::int64_t i = 0;
    std::memcpy(&i, payload.data(), 8);
    value = static_cast<double>(i);
    return true;
  }
  if (type == "boolean" && payload.size() == 1) {
    value = payload[0] != 0 ? 1.0 : 0.0;
    return true;
  }
  return false;
}

}  // namespace driveid
