#include "io/column_expression.h"

#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "core/errors.h"

namespace driveid {
namespace {

std::string Trimmed(const std::string& s) {
  std::size_t b = 0, e = s.size();
  while (b < e && (s[b] == ' ' || s[b] == '\t')) ++b;
  while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\t')) --e;
  return s.substr(b, e - b);
}

std::optional<double> Number(const std::string& word) {
  const char* begin = word.data();
  const char* end = word.data() + word.size();
  if (begin != end && *begin == '+') ++begin;
  double value = 0.0;
  const auto result = std::from_chars(begin, end, value);
  if (begin == end || result.ec != std::errc() || result.ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

}  // namespace

ColumnExpression ParseColumnExpression(const std::string& option, const std::string& text,
                                       const std::function<bool(const std::string&)>& is_column,
                                       const std::function<std::optional<double>(const std::string&)>& scalar) {
  ColumnExpression out;
  out.text = text;
  const std::string whole = Trimmed(text);
  if (whole.empty()) throw OptionError(fmt::format("{}: empty expression", option));
  if (is_column(whole)) {
    out.reference = whole;
    return out;
  }
  // Split at '*' and '/' outside parentheses: factors with their operator.
  std::vector<std::pair<char, std::string>> factors;
  char op = '*';
  int depth = 0;
  std::string current;
  for (char c : whole) {
    if (c == '(') ++depth;
    if (c == ')') --depth;
    if (depth == 0 && (c == '*' || c == '/')) {
      factors.emplace_back(op, Trimmed(current));
      op = c;
      current.clear();
    } else {
      current += c;
    }
  }
  factors.emplace_back(op, Trimmed(current));
  for (const auto& [how, word] : factors) {
    if (word.empty()) {
      throw OptionError(fmt::format("{}: malformed expression (an operand is missing); expected COLUMN, or COLUMN "
                                    "multiplied or divided by numbers, pi or scalars (docs/formats.md)", option));
    }
    double value = 0.0;
    if (const auto number = Number(word)) {
      value = *number;
    } else if (word == "pi") {
      value = M_PI;
    } else if (is_column(word)) {
      if (!out.reference.empty()) {
        throw OptionError(fmt::format("{}: two columns ('{}' and '{}'); an expression scales one column", option,
                                      out.reference, word));
      }
      if (how == '/') throw OptionError(fmt::format("{}: the column '{}' may not be a divisor", option, word));
      out.reference = word;
      continue;
    } else if (const auto named = scalar(word)) {
      value = *named;
    } else {
      throw OptionError(fmt::format("{}: '{}' is neither a column of the log, a number, pi, nor a scalar of the file",
                                    option, word));
    }
    if (how == '/') {
      if (value == 0.0) throw OptionError(fmt::format("{}: division by zero ('{}')", option, word));
      out.factor /= value;
    } else {
      out.factor *= value;
    }
  }
  if (out.reference.empty()) {
    throw OptionError(fmt::format("{}: no column in the expression (a constant column is not a log)", option));
  }
  if (!std::isfinite(out.factor) || out.factor == 0.0) {
    throw OptionError(fmt::format("{}: the factor is {} (not a finite non-zero number)", option, out.factor));
  }
  return out;
}

}  // namespace driveid
