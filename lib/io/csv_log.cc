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

namespace driveid {
namespace {

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

// Trims blanks (and a trailing CR) from both ends of [begin, end).
void Trim(const char*& begin, const char*& end) {
  while (begin < end && IsBlank(*begin)) ++begin;
  while (end > begin && IsBlank(end[-1])) --end;
}

// Quotes a field for an error message: at most 40 characters, control and
// non-ASCII bytes escaped so that binary garbage cannot mess up a terminal.
std::string Quote(const char* begin, const char* end) {
  std::string out = "\"";
  const std::size_t length = static_cast<std::size_t>(end - begin);
  const std::size_t shown = length > 40 ? 40 : length;
  for (std::size_t i = 0; i < shown; ++i) {
    const unsigned char c = static_cast<unsigned char>(begin[i]);
    if (c < 0x20 || c >= 0x7f || c == '"' || c == '\\') {
      out += fmt::format("\\x{:02x}", c);
    } else {
      out += static_cast<char>(c);
    }
  }
  if (shown < length) out += fmt::format("...\" ({} bytes)", length);
  else out += "\"";
  return out;
}

// Splits the header line into trimmed names (surrounding double quotes removed).
std::vector<std::string> SplitHeader(const char* begin, const char* end) {
  std::vector<std::string> names;
  const char* field = begin;
  for (const char* p = begin;; ++p) {
    if (p == end || *p == ',') {
      const char* b = field;
      const char* e = p;
      Trim(b, e);
      if (e - b >= 2 && *b == '"' && e[-1] == '"') {
        ++b;
        --e;
      }
      names.emplace_back(b, e);
      if (p == end) break;
      field = p + 1;
    }
  }
  return names;
}

}  // namespace

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
    if (limits.max_line_bytes > 0) {
      const char* begin = chunk.data();
      const char* end = begin + n;
      while (begin < end) {
        const char* newline = static_cast<const char*>(std::memchr(begin, '\n', static_cast<std::size_t>(end - begin)));
        line_length += static_cast<std::size_t>((newline ? newline : end) - begin);
        if (line_length > limits.max_line_bytes) {
          ::close(fd);
          throw InputError(fmt::format("{}:{}: line longer than {} bytes", path,
                                       1 + std::count(text.begin(), text.end(), '\n') +
                                           std::count(static_cast<const char*>(chunk.data()), begin, '\n'),
                                       limits.max_line_bytes));
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
      throw InputError(fmt::format("--col {}: expected NAME=HEADER", entry));
    }
    map[entry.substr(0, eq)] = entry.substr(eq + 1);
  }
  return map;
}

CsvLog ParseCsvLog(const std::string& path, const std::string& text,
                   const std::vector<std::string>& required, const CsvReadOptions& options) {
  CsvLog log;
  log.path = path;
  log.names = required;
  log.columns.resize(required.size());
  // Every --col must name a column of this log format.
  std::vector<std::string> known;
  for (const auto& entry : required) {
    for (std::size_t start = 0;;) {
      const std::size_t bar = entry.find('|', start);
      known.push_back(entry.substr(start, bar == std::string::npos ? bar : bar - start));
      if (bar == std::string::npos) break;
      start = bar + 1;
    }
  }
  for (const auto& [name, header_name] : options.column_map) {
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      throw OptionError(fmt::format("--col {}={}: this log has no column '{}' (its columns: {})", name, header_name,
                                    name, fmt::join(known, ", ")));
    }
  }

  const char* p = text.data();
  const char* const end = text.data() + text.size();
  if (text.size() >= 3 && std::memcmp(p, "\xEF\xBB\xBF", 3) == 0) p += 3;  // UTF-8 BOM

  int line = 0;
  std::vector<int> slot_of_field;  // header field index -> output column, or -1
  std::vector<std::string> header;
  int header_line = 0;
  std::size_t field_count = 0;

  while (p < end) {
    const char* newline = static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p)));
    const char* line_end = newline ? newline : end;
    ++line;
    if (static_cast<std::size_t>(line_end - p) > options.max_line_bytes) {
      throw InputError(fmt::format("{}:{}: line longer than {} bytes", path, line, options.max_line_bytes));
    }
    const char* b = p;
    const char* e = line_end;
    p = newline ? newline + 1 : end;
    Trim(b, e);
    if (b == e) continue;  // blank line
    if (*b == '#') {
      log.comments.emplace_back(b + 1, e);
      continue;
    }
    if (header.empty()) {
      header = SplitHeader(b, e);
      header_line = line;
      field_count = header.size();
      slot_of_field.assign(field_count, -1);
      std::unordered_set<std::string_view> seen;  // linear in the number of columns
      for (std::size_t i = 0; i < field_count; ++i) {
        if (header[i].empty()) {
          throw InputError(fmt::format("{}:{}: header field {} is empty", path, line, i + 1));
        }
        if (!seen.insert(header[i]).second) {
          throw InputError(fmt::format("{}:{}: column '{}' appears twice in the header", path, line, header[i]));
        }
      }
      for (std::size_t k = 0; k < required.size(); ++k) {
        // Alternatives "a|b": the first one present wins.
        std::vector<std::string> alternatives;
        for (std::size_t start = 0;;) {
          const std::size_t bar = required[k].find('|', start);
          alternatives.push_back(required[k].substr(start, bar == std::string::npos ? bar : bar - start));
          if (bar == std::string::npos) break;
          start = bar + 1;
        }
        std::size_t found = field_count;
        std::string wanted_all;
        for (const auto& name : alternatives) {
          const auto mapped = options.column_map.find(name);
          const std::string& wanted = mapped == options.column_map.end() ? name : mapped->second;
          wanted_all += (wanted_all.empty() ? "'" : "' or '") + wanted;
          for (std::size_t i = 0; i < field_count && found == field_count; ++i) {
            if (header[i] == wanted) {
              found = i;
              log.names[k] = name;
            }
          }
          if (found != field_count) break;
        }
        if (found == field_count) {
          std::string have;
          for (std::size_t i = 0; i < field_count && i < 12; ++i) have += (i ? ", " : "") + Quote(header[i].data(), header[i].data() + header[i].size());
          throw InputError(fmt::format("{}:{}: missing column {}' (header has {}; map another name with --col {}=HEADER)",
                                       path, line, wanted_all, have, alternatives.front()));
        }
        if (slot_of_field[found] >= 0) {
          throw OptionError(fmt::format("--col: '{}' and '{}' would both read column '{}' of {}",
                                        log.names[static_cast<std::size_t>(slot_of_field[found])], log.names[k],
                                        header[found], path));
        }
        slot_of_field[found] = static_cast<int>(k);
      }
      continue;
    }
    // Data row: exactly field_count fields; requested ones must be finite numbers.
    std::size_t field = 0;
    const char* field_begin = b;
    for (const char* q = b;; ++q) {
      if (q == e || *q == ',') {
        if (field >= field_count) {
          throw InputError(fmt::format("{}:{}: {} fields, but the header (line {}) has {}", path, line,
                                       1 + static_cast<std::size_t>(std::count(b, e, ',')), header_line, field_count));
        }
        const int slot = slot_of_field[field];
        if (slot >= 0) {
          const char* fb = field_begin;
          const char* fe = q;
          Trim(fb, fe);
          const std::string& name = header[field];
          if (fb == fe) throw InputError(fmt::format("{}:{}: column '{}': empty cell", path, line, name));
          const char* number_begin = (*fb == '+' && fe - fb > 1) ? fb + 1 : fb;
          double value = 0.0;
          const auto result = std::from_chars(number_begin, fe, value);
          if (result.ec == std::errc::result_out_of_range) {
            throw InputError(fmt::format("{}:{}: column '{}': number out of range: {}", path, line, name, Quote(fb, fe)));
          }
          if (result.ec != std::errc() || result.ptr != fe) {
            throw InputError(fmt::format("{}:{}: column '{}': not a number: {}", path, line, name, Quote(fb, fe)));
          }
          if (!std::isfinite(value)) {
            throw InputError(fmt::format("{}:{}: column '{}': not a finite number: {}", path, line, name, Quote(fb, fe)));
          }
          log.columns[static_cast<std::size_t>(slot)].push_back(value);
        }
        ++field;
        if (q == e) break;
        field_begin = q + 1;
      }
    }
    if (field != field_count) {
      throw InputError(fmt::format("{}:{}: {} fields, but the header (line {}) has {}", path, line, field,
                                   header_line, field_count));
    }
    log.line_numbers.push_back(line);
  }

  if (header.empty()) throw InputError(fmt::format("{}: empty file: no header row", path));
  if (log.line_numbers.empty()) {
    throw InputError(fmt::format("{}:{}: no data rows after the header", path, header_line));
  }
  if (!options.time_column.empty()) {
    for (std::size_t k = 0; k < required.size(); ++k) {
      if (log.names[k] != options.time_column) continue;
      const auto& time = log.columns[k];
      for (std::size_t r = 1; r < time.size(); ++r) {
        if (!(time[r] > time[r - 1])) {
          throw InputError(fmt::format("{}:{}: column '{}': time not strictly increasing ({} after {})", path,
                                       log.line_numbers[r], options.time_column, time[r], time[r - 1]));
        }
      }
    }
  }
  return log;
}

CsvLog ReadCsvLog(const std::string& path, const std::vector<std::string>& required,
                  const CsvReadOptions& options) {
  return ParseCsvLog(path, ReadFileToString(path), required, options);
}

}  // namespace driveid
