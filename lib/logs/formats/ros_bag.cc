#include "logs/formats/ros_bag.h"

#include <cctype>
#include <filesystem>
#include <optional>
#include <memory>

#include <lz4frame.h>
#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <fastcdr/exceptions/Exception.h>
#include <fmt/format.h>
#include <sqlite3.h>
#include <yaml-cpp/yaml.h>

#include "core/errors.h"
#include "system/byte_source.h"
#include "logs/formats/joint_state_rows.h"
#include "logs/formats/ros_source.h"

namespace driveid {
namespace {

constexpr const char* kJointStateType = "sensor_msgs/msg/JointState";

// A read-only SQLite connection: onto bytes in memory (no copy), or onto a
// file by its path, opened immutable (no lock, no journal).
class Database {
 public:
  explicit Database(ByteSource& bytes) : path_(bytes.name()) {
    if (const std::string* memory = bytes.memory()) {
      if (sqlite3_open_v2(":memory:", &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_MEMORY, nullptr) != SQLITE_OK) {
        Fail("cannot open an in-memory database");
      }
      auto* data = reinterpret_cast<unsigned char*>(const_cast<char*>(memory->data()));
      const auto size = static_cast<sqlite3_int64>(memory->size());
      if (sqlite3_deserialize(db_, "main", data, size, size, SQLITE_DESERIALIZE_READONLY) != SQLITE_OK) {
        Fail("not a readable SQLite database");
      }
    } else if (sqlite3_open_v2(FileUri(path_).c_str(), &db_, SQLITE_OPEN_READONLY | SQLITE_OPEN_URI, nullptr) != SQLITE_OK) {
      Fail("not a readable SQLite database");
    }
    sqlite3_db_config(db_, SQLITE_DBCONFIG_DEFENSIVE, 1, nullptr);
  }
  ~Database() { sqlite3_close(db_); }
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;

  // Runs `sql`, handing each row to `row`; InputError on any SQLite error.
  template <typename Row>
  void Query(const char* sql, Row row, std::optional<long long> bind = std::nullopt) {
    sqlite3_stmt* statement = nullptr;
    if (sqlite3_prepare_v2(db_, sql, -1, &statement, nullptr) != SQLITE_OK) Fail("not a rosbag2 SQLite3 bag");
    std::unique_ptr<sqlite3_stmt, int (*)(sqlite3_stmt*)> guard(statement, sqlite3_finalize);
    if (bind) sqlite3_bind_int64(statement, 1, *bind);
    int status = 0;
    while ((status = sqlite3_step(statement)) == SQLITE_ROW) row(statement);
    if (status != SQLITE_DONE) Fail("corrupt or unreadable");
  }

 private:
  [[noreturn]] void Fail(const char* what) const {
    throw InputError(fmt::format("{}: {}: {}", path_, what, db_ != nullptr ? sqlite3_errmsg(db_) : "out of memory"));
  }
  // "file:PATH?immutable=1" with every byte but [A-Za-z0-9/._~-] escaped.
  static std::string FileUri(const std::string& path) {
    std::string uri = "file:";
    for (const unsigned char c : path) {
      if (std::isalnum(c) != 0 || c == '/' || c == '.' || c == '_' || c == '~' || c == '-') uri += static_cast<char>(c);
      else uri += fmt::format("%{:02X}", c);
    }
    return uri + "?immutable=1";
  }
  std::string path_;
  sqlite3* db_ = nullptr;
};

std::string Column(sqlite3_stmt* s, int k) {
  const unsigned char* text = sqlite3_column_text(s, k);
  return text != nullptr ? reinterpret_cast<const char*>(text) : "";
}

// A sequence's element count, checked against the bytes left (each element
// takes at least `least` bytes) before anything is allocated.
std::uint32_t Count(eprosima::fastcdr::Cdr& cdr, std::size_t size, std::size_t least, const char* field) {
  std::uint32_t n = 0;
  cdr >> n;
  const std::size_t left = size - std::min(size, cdr.getSerializedDataLength());
  if (static_cast<std::uint64_t>(n) * least > left) {
    throw MessageError(fmt::format("{} claims {} elements, {} bytes remain", field, n, left));
  }
  return n;
}

}  // namespace

bool LooksLikeSqlite(std::string_view text) { return text.compare(0, 16, std::string("SQLite format 3\0", 16)) == 0; }

std::string ResolveBagPath(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_directory(path, error)) return path;
  const std::filesystem::path folder(path);
  std::vector<std::string> files;
  if (std::filesystem::is_regular_file(folder / "metadata.yaml", error)) {
    try {
      const YAML::Node info = YAML::LoadFile((folder / "metadata.yaml").string())["rosbag2_bagfile_information"];
      for (const auto& file : info["relative_file_paths"]) files.push_back(file.as<std::string>());
    } catch (const YAML::Exception& e) {
      throw InputError(fmt::format("{}/metadata.yaml: not a rosbag2 metadata file: {}", path, e.what()));
    }
  } else {
    for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
      const std::string ext = entry.path().extension().string();
      if (entry.is_regular_file() && (ext == ".db3" || ext == ".mcap")) files.push_back(entry.path().filename().string());
    }
  }
  if (files.empty()) {
    throw InputError(fmt::format("{}: is a directory, not a file (nor a rosbag2 bag's folder: no .db3 or .mcap in it)", path));
  }
  if (files.size() > 1) {
    throw InputError(fmt::format("{}: a bag split over {} files ({}): give them one by one, each a log", path,
                                 files.size(), fmt::join(files, ", ")));
  }
  const std::filesystem::path file(files.front());
  if (file.is_absolute() || file.string().find("..") != std::string::npos) {
    throw InputError(fmt::format("{}/metadata.yaml: storage file {} lies outside the bag's folder", path, file.string()));
  }
  return (folder / file).string();
}

std::vector<RosTopic> ReadSqliteBag(ByteSource& bytes, const JointStateSinks& sinks) {
  Database db(bytes);
  const std::string& path = bytes.name();
  std::vector<RosTopic> topics;
  std::vector<long long> ids;
  db.Query("SELECT id, name, type, serialization_format FROM topics ORDER BY id", [&](sqlite3_stmt* s) {
    ids.push_back(sqlite3_column_int64(s, 0));
    topics.push_back({Column(s, 1), Column(s, 2), Column(s, 3), 0, 0, 0});
  });
  db.Query("SELECT topic_id, COUNT(*), MIN(timestamp), MAX(timestamp) FROM messages GROUP BY topic_id",
           [&](sqlite3_stmt* s) {
             const long long id = sqlite3_column_int64(s, 0);
             for (std::size_t i = 0; i < ids.size(); ++i) {
               if (ids[i] != id) continue;
               topics[i].messages = static_cast<std::size_t>(sqlite3_column_int64(s, 1));
               topics[i].first_ns = sqlite3_column_int64(s, 2);
               topics[i].last_ns = sqlite3_column_int64(s, 3);
             }
           });
  JointStateMessage message;
  for (std::size_t i = 0; i < topics.size(); ++i) {
    if (topics[i].type != kJointStateType || topics[i].serialization != "cdr") continue;
    JointStateRows* sink = sinks(topics[i].name);
    if (sink == nullptr) continue;
    std::size_t index = 0;
    db.Query(
        "SELECT timestamp, data FROM messages WHERE topic_id = ?1 ORDER BY id",
        [&](sqlite3_stmt* s) {
          const auto* data = static_cast<const char*>(sqlite3_column_blob(s, 1));
          const auto size = static_cast<std::size_t>(sqlite3_column_bytes(s, 1));
          const std::int64_t receive = sqlite3_column_int64(s, 0);
          ++index;
          try {
            DecodeJointStateCdr(data, size, message);
          } catch (const MessageError& e) {
            throw InputError(fmt::format("{}: {} message {} (received at {:.9f} s): {}", path, topics[i].name, index,
                                         static_cast<double>(receive) * 1e-9, e.what()));
          }
          message.receive_ns = receive;
          sink->Add(message);
        },
        ids[i]);
  }
  bytes.CheckUnchanged();
  return topics;
}

JointStateMessage DecodeJointStateCdr(const std::string& where, const char* data, std::size_t size) {
  JointStateMessage m;
  try {
    DecodeJointStateCdr(data, size, m);
  } catch (const MessageError& e) {
    throw InputError(fmt::format("{}: {}", where, e.what()));
  }
  return m;
}

void DecodeJointStateCdr(const char* data, std::size_t size, JointStateMessage& m) {
  if (data == nullptr || size < 4) throw MessageError(fmt::format("{} bytes: not a CDR message", size));
  eprosima::fastcdr::FastBuffer buffer(const_cast<char*>(data), size);
  eprosima::fastcdr::Cdr cdr(buffer, eprosima::fastcdr::Cdr::DEFAULT_ENDIAN, eprosima::fastcdr::Cdr::DDS_CDR);
  try {
    cdr.read_encapsulation();
    std::int32_t sec = 0;
    std::uint32_t nanosec = 0;
    std::string frame;
    cdr >> sec >> nanosec >> frame;
    if (nanosec >= 1'000'000'000U) throw MessageError(fmt::format("header.stamp.nanosec = {}", nanosec));
    m.stamp_ns = static_cast<std::int64_t>(sec) * 1'000'000'000 + nanosec;
    const std::uint32_t names = Count(cdr, size, 5, "name[]");
    m.name.resize(names);
    for (auto& n : m.name) cdr >> n;
    for (auto* values : {&m.position, &m.velocity, &m.effort}) {
      const std::uint32_t n = Count(cdr, size, 8, values == &m.position ? "position[]"
                                                  : values == &m.velocity ? "velocity[]"
                                                                          : "effort[]");
      values->resize(n);
      for (double& v : *values) cdr >> v;
    }
  } catch (const eprosima::fastcdr::exception::Exception& e) {
    throw MessageError(fmt::format("not a sensor_msgs/msg/JointState in CDR ({})", e.what()));
  }
}

std::string InflateLz4Frame(const char* data, std::size_t size, std::string& out) {
  LZ4F_dctx* context = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&context, LZ4F_VERSION))) return "no lz4 context";
  std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> guard(context, LZ4F_freeDecompressionContext);
  std::size_t written = 0, read = 0;
  while (read < size) {
    std::size_t out_size = out.size() - written, in_size = size - read;
    const std::size_t hint = LZ4F_decompress(context, out.data() + written, &out_size, data + read, &in_size, nullptr);
    if (LZ4F_isError(hint)) return LZ4F_getErrorName(hint);
    written += out_size;
    read += in_size;
    if (hint == 0 || (out_size == 0 && in_size == 0)) break;  // the frame's end, or more output than claimed
  }
  out.resize(written);
  return "";
}

// A rosbag2 SQLite3 file (`.db3`); a rosbag2 folder (either storage) is read through its storage file.
DRIVEID_LOG_FORMAT(ros_bag) {
  LogFormat format = BagLogFormat("rosbag2-sqlite3", LooksLikeSqlite, {"rosbag2 SQLite3", ReadSqliteBag, {}});
  format.folder = ResolveBagPath;
  return format;
}

}  // namespace driveid
