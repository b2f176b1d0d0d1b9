#include "logs/transpose_table.h"

#include <cstddef>
#include <vector>

#include <fmt/format.h>

#include "core/errors.h"

namespace driveid {
namespace {

std::string Trim(const std::string& s) {
  const std::size_t first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

std::vector<std::string> Split(const std::string& line, char delimiter) {
  std::vector<std::string> cells;
  if (delimiter == ' ') {
    std::size_t k = 0;
    while (true) {
      k = line.find_first_not_of(" \r", k);
      if (k == std::string::npos) break;
      const std::size_t end = line.find_first_of(" \r", k);
      cells.push_back(line.substr(k, end == std::string::npos ? std::string::npos : end - k));
      if (end == std::string::npos) break;
      k = end;
    }
    return cells;
  }
  std::size_t start = 0;
  while (true) {
    const std::size_t end = line.find(delimiter, start);
    cells.push_back(Trim(line.substr(start, end == std::string::npos ? std::string::npos : end - start)));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return cells;
}

}  // namespace

std::string TransposeTable(const std::string& path, const std::string& text) {
  std::string comments;
  std::vector<std::vector<std::string>> rows;
  char delimiter = 0;
  std::size_t first_line = 0;
  std::size_t line_number = 0;
  for (std::size_t start = 0; start < text.size();) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(start, end - start);
    start = end + 1;
    ++line_number;
    const std::string trimmed = Trim(line);
    if (trimmed.empty()) continue;
    if (trimmed[0] == '#') {
      comments += trimmed + "\n";
      continue;
    }
    if (delimiter == 0) {
      delimiter = ' ';
      for (char d : {',', ';', '\t'}) {
        if (trimmed.find(d) != std::string::npos) {
          delimiter = d;
          break;
        }
      }
      first_line = line_number;
    }
    rows.push_back(Split(trimmed, delimiter));
    if (rows.back().size() != rows.front().size()) {
      throw InputError(fmt::format("{}:{}: ‹transpose›: {} cells, line {} has {} (each row is one signal)", path,
                                   line_number, rows.back().size(), first_line, rows.front().size()));
    }
  }
  if (rows.empty()) throw InputError(fmt::format("{}: ‹transpose›: no rows", path));
  std::string out = comments;
  for (std::size_t j = 0; j < rows.front().size(); ++j) {
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (i > 0) out += ',';
      out += rows[i][j];
    }
    out += '\n';
  }
  return out;
}

}  // namespace driveid
