#include "logs/log_files.h"

#include <algorithm>
#include <utility>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"
#include "system/byte_source.h"
#include "logs/log_format.h"
#include "system/sha256.h"
#include "logs/transpose_table.h"

namespace driveid {

bool LogFileRequest::IsValid(std::string* error) const {
  return OptionCheck(error).Require(!path.empty(), "a log file needs a path");
}

LogFileBytes ReadLogFile(const std::string& path, const ReadLimits& limits, bool hash) {
  const std::string resolved = ResolveLogPath(path);
  if (auto file = OpenFileBytes(resolved); file && file->size() <= limits.max_bytes) {
    std::string head(file->View(0, std::min<std::uint64_t>(file->size(), kLogSniffBytes)));
    if (SniffLogFormat(head).streamed) {
      return {std::move(head), hash ? Sha256Hex(*file) : "", resolved};
    }
  }
  LogFileBytes out;
  out.text = ReadFileToString(resolved, limits);
  if (hash) out.sha256 = Sha256Hex(out.text);
  return out;
}

void ReadLogFiles(const std::vector<LogFileRequest>& files, const std::vector<std::string>& columns,
                  const LogInputOptions& options, const ReadLimits& limits, bool transpose,
                  std::vector<DataFileRecord>& records, const std::function<void(CsvLog)>& take) {
  std::vector<std::pair<std::string, std::string>> seen;  // hash, file
  for (const LogFileRequest& file : files) {
    RequireValid(file);
    const std::string& path = file.path;
    const LogFileBytes raw = ReadLogFile(path, limits, true);
    const std::string& hash = raw.sha256;
    const std::string text = transpose ? TransposeTable(path, raw.text) : raw.text;
    LogInputOptions file_options = options;
    file_options.selection.stream_file = raw.stream_file;
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
    for (CsvLog& csv : ReadLogs(path, text, joins, columns, file_options)) {
      DataFileRecord record{path, hash, static_cast<int>(csv.rows()), csv.segment, csv.notes};
      record.notes.insert(record.notes.end(), join_notes.begin(), join_notes.end());
      records.push_back(std::move(record));
      take(std::move(csv));
    }
  }
}

}  // namespace driveid
