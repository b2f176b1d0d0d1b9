#include "io/log_files.h"

#include "io/ros_bag.h"

#include <utility>

#include <fmt/format.h>

#include "core/errors.h"
#include "io/sha256.h"
#include "io/transpose_table.h"

namespace driveid {

void ReadLogFiles(const std::vector<LogFileRequest>& files, const std::vector<std::string>& columns,
                  const LogInputOptions& options, const ReadLimits& limits, bool transpose,
                  std::vector<DataFileRecord>& records, const std::function<void(CsvLog)>& take) {
  std::vector<std::pair<std::string, std::string>> seen;  // hash, file
  for (const LogFileRequest& file : files) {
    const std::string& path = file.path;
    const std::string raw = ReadFileToString(ResolveBagPath(path), limits);  // a rosbag2 folder: its storage file
    const std::string hash = Sha256Hex(raw);
    const std::string text = transpose ? TransposeTable(path, raw) : raw;
    for (const auto& [earlier_hash, earlier] : seen) {
      if (earlier_hash == hash) {
        throw OptionError(fmt::format("{}: the same data as {} (sha256 {}): give each log once", path, earlier,
                                      hash.substr(0, 12)));
      }
    }
    seen.emplace_back(hash, path);
    std::vector<std::string> join_notes;
    std::string join_text;
    std::vector<JoinedFile> joins;
    if (!file.join_path.empty()) {
      join_text = ReadFileToString(file.join_path, limits);
      joins.push_back({file.join_path, &join_text, file.join_timing});
      join_notes.push_back(fmt::format("joined with {} (sha256 {})", file.join_path, Sha256Hex(join_text)));
    }
    for (CsvLog& csv : ReadLogs(path, text, joins, columns, options)) {
      DataFileRecord record{path, hash, static_cast<int>(csv.rows()), csv.segment, csv.notes};
      record.notes.insert(record.notes.end(), join_notes.begin(), join_notes.end());
      records.push_back(std::move(record));
      take(std::move(csv));
    }
  }
}

}  // namespace driveid
