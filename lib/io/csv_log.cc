#include "io/csv_log.h"

#include <algorithm>
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <string_view>
#include <unordered_set>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"
#include "io/log_input.h"

namespace driveid {

bool CsvReadOptions::IsValid(std::string* error) const {
  OptionCheck check(error);
  for (const auto& [name, header] : column_map) {
    check.Require(!name.empty() && !header.empty(), fmt::format("‹col› '{}={}': a name and a header", name, header));
  }
  return check;
}

const std::vector<double>& CsvLog::column(const std::string& name) const {
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (names[k] == name) return columns[k];
  }
  throw std::out_of_range("CsvLog::column: no column '" + name + "'");
}

std::string ReadFileToString(const std::string& path, const ReadLimits& limits) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw InputError(fmt::format("{}: cannot open file for reading: {}", path, std::strerror(errno)));
  struct stat status {};
  if (::fstat(fd, &status) == 0 && S_ISDIR(status.st_mode)) {
    ::close(fd);
    throw InputError(fmt::format("{}: is a directory, not a file", path));
  }
  // Read in chunks with the limits enforced as the bytes arrive, so that an
  // endless input (/dev/zero, a FIFO) fails fast instead of filling memory.
  std::string text;
  if (S_ISREG(status.st_mode) && status.st_size > 0) {
    text.reserve(static_cast<std::size_t>(std::min<off_t>(status.st_size, static_cast<off_t>(limits.max_bytes) + 1)));
  }
  std::size_t line_length = 0;
  std::size_t max_line_bytes = limits.max_line_bytes;
  bool first_chunk = limits.lines_unless_structured;
  std::vector<char> chunk(1 << 16);
  for (;;) {
    const ssize_t got = ::read(fd, chunk.data(), chunk.size());
    if (got < 0) {
      if (errno == EINTR) continue;
      const int error = errno;
      ::close(fd);
      throw InputError(fmt::format("{}: read error: {}", path, std::strerror(error)));
    }
    if (got == 0) break;
    const std::size_t n = static_cast<std::size_t>(got);
    if (text.size() + n > limits.max_bytes) {
      ::close(fd);
      throw InputError(fmt::format("{}: larger than {} bytes ({})", path, limits.max_bytes, limits.max_bytes_hint));
    }
    if (first_chunk) {
      // JSON (SysId writes one long line), MAT and HDF5 files are not lines.
      first_chunk = false;
      std::size_t i = n >= 3 && std::memcmp(chunk.data(), "\xEF\xBB\xBF", 3) == 0 ? 3 : 0;  // byte-order mark
      while (i < n && (chunk[i] == ' ' || chunk[i] == '\n' || chunk[i] == '\r' || chunk[i] == '\t')) ++i;
      const std::string_view head(chunk.data() + i, n - i);
      if (head.substr(0, 1) == "{" || head.substr(0, 7) == "MATLAB " || head.substr(0, 4) == "\x89HDF") {
        max_line_bytes = 0;
      }
    }
    if (max_line_bytes > 0) {
      const char* begin = chunk.data();
      const char* end = begin + n;
      while (begin < end) {
        const char* newline = static_cast<const char*>(std::memchr(begin, '\n', static_cast<std::size_t>(end - begin)));
        line_length += static_cast<std::size_t>((newline ? newline : end) - begin);
        if (line_length > max_line_bytes) {
          ::close(fd);
          throw InputError(fmt::format("{}:{}: line longer than {} bytes", path,
                                       1 + std::count(text.begin(), text.end(), '\n') +
                                           std::count(static_cast<const char*>(chunk.data()), begin, '\n'),
                                       max_line_bytes));
        }
        if (newline == nullptr) break;
        line_length = 0;
        begin = newline + 1;
      }
    }
    text.append(chunk.data(), n);
  }
  ::close(fd);
  return text;
}

void RequireFiniteColumns(const std::vector<std::pair<std::string, const std::vector<double>*>>& columns,
                          const std::vector<double>& time) {
  for (const auto& [name, values] : columns) {
    if (values->size() != time.size()) {
      throw OutputError(fmt::format("column '{}' holds {} values for {} times; nothing written", name, values->size(),
                                    time.size()));
    }
  }
  for (const auto& [name, values] : columns) {
    for (std::size_t k = 0; k < values->size(); ++k) {
      if (!std::isfinite((*values)[k])) {
        throw OutputError(fmt::format(
            "column '{}' would be {} at t = {} s (sample {}): the parameters or options overflow the simulation; "
            "nothing written",
            name, (*values)[k], k < time.size() ? time[k] : 0.0, k + 1));
      }
    }
  }
}

std::map<std::string, std::string> ParseColumnMap(const std::vector<std::string>& entries) {
  std::map<std::string, std::string> map;
  for (const auto& entry : entries) {
    const auto eq = entry.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == entry.size()) {
      throw InputError(fmt::format("‹col› {}: expected NAME=HEADER", entry));
    }
    map[entry.substr(0, eq)] = entry.substr(eq + 1);
  }
  return map;
}

CsvLog ParseCsvLog(const std::string& path, const std::string& text,
                   const std::vector<std::string>& required, const CsvReadOptions& options) {
  RequireValid(options);
  LogInputOptions input;
  input.columns = options.column_map;
  input.time_column = options.time_column;
  input.csv.max_line_bytes = options.max_line_bytes;
  std::vector<CsvLog> logs = ReadLogs(path, text, {}, required, input);
  if (logs.size() != 1) {
    throw InputError(fmt::format("{}: {} logs in one file (a SysId file): this reader takes one", path, logs.size()));
  }
  return std::move(logs.front());
}

CsvLog ReadCsvLog(const std::string& path, const std::vector<std::string>& required,
                  const CsvReadOptions& options) {
  return ParseCsvLog(path, ReadFileToString(path), required, options);
}

}  // namespace driveid
