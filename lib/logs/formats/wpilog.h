// WPILib DataLog (.wpilog, version 1.0), read from its published
// specification (docs/formats.md#wpilog): the header "WPILOG", a 16-bit
// version 0x0100 and an extra-header string; then records, each a length
// byte (bits 0-1: entry id bytes - 1, 2-3: payload size bytes - 1, 4-6:
// timestamp bytes - 1), the entry id, the payload size and the timestamp
// [µs], little-endian, then the payload. Entry 0 is control: Start (0; id,
// name, type, metadata), Finish (1; id), Set metadata (2; id, metadata).
// Every size a record claims is checked against the file; a record cut
// short is refused with its offset. Records of no started entry are
// counted, not read. A timestamp of 8 bytes with its top bit set is a
// negative number (retained NetworkTables values): such records are left
// out, counted per entry, never read as 1.8e13 s.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace driveid {

/// True when `text` starts with the WPILog header.
bool LooksLikeWpilog(std::string_view text);

/// One entry of the log (its last Start), with what its records hold.
struct WpilogEntry {
  std::uint32_t id = 0;
  std::string name, type, metadata;
  std::size_t records = 0;           ///< data records with a timestamp >= 0
  std::size_t negative_records = 0;  ///< left out: negative timestamps
  std::int64_t first_us = 0, last_us = 0;
  std::size_t start_order = 0;       ///< which Start made it (0, 1, ...): ids may be reused
};

/// A data record as read: its entry (valid during the visit only),
/// timestamp [µs] and payload.
struct WpilogRecord {
  const WpilogEntry* entry = nullptr;
  std::int64_t timestamp_us = 0;
  std::string_view payload;
  std::size_t offset = 0;  ///< of the record in the file (for messages)
};

/// The entries of a log and the counts the reader met.
struct WpilogIndex {
  std::uint16_t version = 0;
  std::string extra_header;
  std::vector<WpilogEntry> entries;   ///< in the order started
  std::size_t orphan_records = 0;     ///< records of no started entry
  std::size_t records = 0;            ///< all records, control included
};

/// One pass over the log's records: builds the index and hands each data
/// record with a timestamp >= 0 to `visit` (may be empty). Throws
/// InputError naming `path` and the offset of what is corrupt.
WpilogIndex ReadWpilog(const std::string& path, std::string_view text,
                       const std::function<void(const WpilogRecord&)>& visit = {});

/// A numeric record's value (double, float, int64, boolean); false for
/// another type or a payload of the wrong size.
bool WpilogNumber(const std::string& type, std::string_view payload, double& value);

}  // namespace driveid
