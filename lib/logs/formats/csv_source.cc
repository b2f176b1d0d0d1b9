#include "logs/formats/csv_source.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <fmt/format.h>

#include "core/errors.h"
#include "logs/log_format.h"

namespace driveid {
namespace {

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

void Trim(const char*& begin, const char*& end) {
  while (begin < end && IsBlank(*begin)) ++begin;
  while (end > begin && IsBlank(end[-1])) --end;
}

// A field for an error message: at most 40 characters, control and non-ASCII
// bytes escaped so that binary garbage cannot mess up a terminal.
std::string Quote(const char* begin, const char* end) {
  std::string out = "\"";
  const std::size_t length = static_cast<std::size_t>(end - begin);
  const std::size_t shown = std::min<std::size_t>(length, 40);
  for (std::size_t i = 0; i < shown; ++i) {
    const unsigned char c = static_cast<unsigned char>(begin[i]);
    if (c < 0x20 || c >= 0x7f || c == '"' || c == '\\') out += fmt::format("\\x{:02x}", c);
    else out += static_cast<char>(c);
  }
  return shown < length ? out + fmt::format("...\" ({} bytes)", length) : out + "\"";
}

// Splits [begin, end) into trimmed fields at `delimiter` (' ' = runs of
// blanks). A field that starts with a double quote runs to the closing one
// (RFC 4180: a delimiter inside is text, "" stands for a quote) and is
// visited without its quotes (a "" inside is passed on as it is); what
// follows its closing quote up to the delimiter is not part of it. A line
// end inside quotes ends the field (a row is one line).
template <typename Visit>
void SplitFields(const char* begin, const char* end, char delimiter, Visit visit) {
  if (delimiter == ' ') {
    const char* p = begin;
    while (p < end) {
      while (p < end && IsBlank(*p)) ++p;
      if (p == end) break;
      const char* field = p;
      while (p < end && !IsBlank(*p)) ++p;
      visit(field, p);
    }
    return;
  }
  const char* p = begin;
  for (;;) {
    const char* start = p;
    while (start < end && IsBlank(*start)) ++start;
    const char* next = nullptr;  // the delimiter after the field, or end
    if (start < end && *start == '"') {
      const char* close = start + 1;
      while (close < end && !(*close == '"' && !(close + 1 < end && close[1] == '"'))) close += *close == '"' ? 2 : 1;
      next = static_cast<const char*>(std::memchr(close, delimiter, static_cast<std::size_t>(end - close)));
      visit(start + 1, std::min(close, end));
    } else {
      next = static_cast<const char*>(std::memchr(start, delimiter, static_cast<std::size_t>(end - start)));
      const char* b = start;
      const char* e = next ? next : end;
      Trim(b, e);
      visit(b, e);
    }
    if (next == nullptr) break;
    p = next + 1;
  }
}

bool ParseNumber(const char* begin, const char* end, double& value, bool& out_of_range) {
  const char* b = (begin < end && *begin == '+' && end - begin > 1) ? begin + 1 : begin;
  const auto result = std::from_chars(b, end, value);
  out_of_range = result.ec == std::errc::result_out_of_range;
  return b != end && result.ec == std::errc() && result.ptr == end;
}

std::string DelimiterText(char d) {
  switch (d) {
    case '\t': return "tab";
    case ' ': return "blanks";
    default: return std::string("'") + d + "'";
  }
}

class CsvSource : public TableSource {
 public:
  CsvSource(std::string path, std::string_view text, const CsvFormat& format)
      : path_(std::move(path)), text_(text), max_line_bytes_(format.max_line_bytes) {
    std::size_t p = 0;
    if (text_.size() >= 3 && std::memcmp(text_.data(), "\xEF\xBB\xBF", 3) == 0) p = 3;  // UTF-8 BOM
    int line = 0;
    bool first = true;
    while (p < text_.size()) {
      const char* b = nullptr;
      const char* e = nullptr;
      const std::size_t next = NextLine(p, ++line, b, e);
      const std::size_t line_start = p;
      p = next;
      if (static_cast<std::size_t>(line) <= format.skip_rows) {
        comments_.emplace_back(b, e);
        continue;
      }
      if (b == e) continue;
      if (*b == '#') {
        comments_.emplace_back(b + 1, e);
        continue;
      }
      if (first) {
        first = false;
        delimiter_ = format.delimiter ? format.delimiter : Detect(b, e);
        std::vector<std::string> fields;
        bool numeric = true;
        SplitFields(b, e, delimiter_, [&](const char* fb, const char* fe) {
          double v = 0.0;
          bool range = false;
          if (!ParseNumber(fb, fe, v, range)) numeric = false;
          fields.emplace_back(fb, fe);
        });
        field_count_ = fields.size();
        if (format.no_header || numeric) {
          names_.assign(field_count_, "");
          data_start_ = line_start;
          data_line_ = line - 1;
          if (!format.no_header) notes_.push_back("no header row: the first row holds numbers (columns are #1 .. #n)");
          ++rows_;
        } else {
          names_ = std::move(fields);
          header_line_ = line;
          data_start_ = next;
          data_line_ = line;
          CheckHeader();
        }
        continue;
      }
      ++rows_;
    }
    if (first) {
      throw InputError(format.skip_rows > 0 && static_cast<std::size_t>(line) <= format.skip_rows
                           ? fmt::format("{}: {} lines, all skipped (skip {}): no header row", path_, line,
                                         format.skip_rows)
                           : fmt::format("{}: empty file: no header row", path_));
    }
    if (format.skip_rows > 0) notes_.push_back(fmt::format("the first {} lines skipped", format.skip_rows));
    if (rows_ == 0) throw InputError(fmt::format("{}:{}: no data rows after the header", path_, header_line_));
    if (delimiter_ != ',') notes_.push_back("delimiter: " + DelimiterText(delimiter_));
    // A last line without its line end: the file may have been cut while it
    // was written (a number cut short still parses). Read, and said.
    if (!text_.empty() && text_.back() != '\n') {
      notes_.push_back(fmt::format("{} line {} has no line end: the file may have been cut while it was written; "
                                   "check that its last row is whole",
                                   kReaderWarning, line));
    }
  }

  std::string path() const override { return path_; }
  std::string format() const override { return "csv"; }
  int header_line() const override { return header_line_; }
  std::vector<std::string> column_names() const override { return names_; }
  std::vector<std::size_t> column_lengths() const override { return std::vector<std::size_t>(field_count_, rows_); }
  std::vector<std::string> notes() const override { return notes_; }
  std::vector<std::string> comments() const override { return comments_; }

  TableData Read(const std::vector<std::size_t>& columns) const override {
    TableData out;
    out.columns.resize(columns.size());
    for (auto& c : out.columns) c.reserve(rows_);
    out.line_numbers.reserve(rows_);
    std::vector<int> slot(field_count_, -1);
    for (std::size_t k = 0; k < columns.size(); ++k) {
      if (slot[columns[k]] < 0) slot[columns[k]] = static_cast<int>(k);
    }
    std::size_t p = data_start_;
    int line = data_line_;
    while (p < text_.size()) {
      const char* b = nullptr;
      const char* e = nullptr;
      p = NextLine(p, ++line, b, e);
      if (b == e || *b == '#') continue;
      std::size_t field = 0;
      SplitFields(b, e, delimiter_, [&](const char* fb, const char* fe) {
        if (field >= field_count_) {  // counted for the message below
          ++field;
          return;
        }
        const int s = slot[field];
        if (s >= 0) {
          // The column's label is built only for a message (not per cell).
          if (fb == fe) throw InputError(fmt::format("{}:{}: column {}: empty cell", path_, line, ColumnLabel(field)));
          double value = 0.0;
          bool out_of_range = false;
          if (!ParseNumber(fb, fe, value, out_of_range)) {
            throw InputError(fmt::format("{}:{}: column {}: {}: {}", path_, line, ColumnLabel(field),
                                         out_of_range ? "number out of range" : "not a number", Quote(fb, fe)));
          }
          if (!std::isfinite(value)) {
            throw InputError(fmt::format("{}:{}: column {}: not a finite number: {}", path_, line, ColumnLabel(field),
                                         Quote(fb, fe)));
          }
          out.columns[static_cast<std::size_t>(s)].push_back(value);
        }
        ++field;
      });
      if (field != field_count_) {
        throw InputError(fmt::format("{}:{}: {} fields, but the {} has {}", path_, line, field,
                                     header_line_ ? fmt::format("header (line {})", header_line_) : "first row",
                                     field_count_));
      }
      out.line_numbers.push_back(line);
    }
    for (std::size_t k = 0; k < columns.size(); ++k) {
      const int s = slot[columns[k]];
      if (static_cast<std::size_t>(s) != k) out.columns[k] = out.columns[static_cast<std::size_t>(s)];
    }
    return out;
  }

 private:
  // The line starting at p: its trimmed bounds; returns the start of the next.
  std::size_t NextLine(std::size_t p, int line, const char*& b, const char*& e) const {
    const char* start = text_.data() + p;
    const char* end = text_.data() + text_.size();
    const char* newline = static_cast<const char*>(std::memchr(start, '\n', static_cast<std::size_t>(end - start)));
    const char* line_end = newline ? newline : end;
    if (static_cast<std::size_t>(line_end - start) > max_line_bytes_) {
      throw InputError(fmt::format("{}:{}: line longer than {} bytes", path_, line, max_line_bytes_));
    }
    b = start;
    e = line_end;
    Trim(b, e);
    return newline ? static_cast<std::size_t>(newline - text_.data()) + 1 : text_.size();
  }

  static char Detect(const char* b, const char* e) {
    for (char d : {',', ';', '\t'}) {
      if (std::find(b, e, d) != e) return d;
    }
    return ' ';
  }

  void CheckHeader() const {
    std::unordered_map<std::string_view, std::size_t> seen;  // linear in the number of columns
    for (std::size_t i = 0; i < names_.size(); ++i) {
      if (names_[i].empty()) throw InputError(fmt::format("{}:{}: header field {} is empty", path_, header_line_, i + 1));
      if (!seen.emplace(names_[i], i).second) {
        throw InputError(fmt::format("{}:{}: column '{}' appears twice in the header", path_, header_line_, names_[i]));
      }
    }
  }

  std::string ColumnLabel(std::size_t field) const {
    return names_[field].empty() ? fmt::format("#{}", field + 1) : "'" + names_[field] + "'";
  }

  std::string path_;
  std::string_view text_;
  std::size_t max_line_bytes_;
  char delimiter_ = ',';
  std::vector<std::string> names_;
  std::vector<std::string> comments_;
  std::vector<std::string> notes_;
  std::size_t field_count_ = 0;
  std::size_t rows_ = 0;
  std::size_t data_start_ = 0;
  int data_line_ = 0;
  int header_line_ = 0;
};

}  // namespace

std::unique_ptr<TableSource> OpenCsvSource(const std::string& path, const std::string& text, const CsvFormat& format) {
  return std::make_unique<CsvSource>(path, text, format);
}

DRIVEID_LOG_FORMAT(csv_source) {
  LogFormat format;
  format.name = "csv";
  format.source = "csv";
  format.kind = "a CSV file";
  format.sniff = [](std::string_view) { return true; };
  format.open = [](const std::string& path, const std::string& text, const CsvFormat& csv, const LogSelection&) {
    std::vector<std::unique_ptr<TableSource>> out;
    out.push_back(OpenCsvSource(path, text, csv));
    return out;
  };
  return format;
}

}  // namespace driveid
