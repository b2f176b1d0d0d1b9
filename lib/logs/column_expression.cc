#include "logs/column_expression.h"

#include <charconv>
#include <cctype>
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

// One term: a column times or divided by numbers, pi and scalars; with
// `constant_allowed` (a term of a sum) also numbers alone (reference "").
ColumnTerm ParseTerm(const std::string& option, const std::string& whole,
                     const std::function<bool(const std::string&)>& is_column,
                     const std::function<std::optional<double>(const std::string&)>& scalar,
                     bool constant_allowed = false) {
  ColumnTerm out;
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
                                    "multiplied or divided by numbers, pi or scalars, or a sum of such terms "
                                    "(docs/formats.md)", option));
    }
    double value = 0.0;
    if (const auto number = Number(word)) {
      value = *number;
    } else if (word == "pi") {
      value = M_PI;
    } else if (is_column(word)) {
      if (!out.reference.empty()) {
        throw OptionError(fmt::format("{}: two columns ('{}' and '{}') in one product; a term scales one column",
                                      option, out.reference, word));
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
  if (out.reference.empty() && !constant_allowed) {
    throw OptionError(fmt::format("{}: no column in the expression (a constant column is not a log)", option));
  }
  if (out.reference.empty()) {
    if (!std::isfinite(out.factor)) {
      throw OptionError(fmt::format("{}: the constant is {} (not a finite number)", option, out.factor));
    }
    return out;
  }
  if (!std::isfinite(out.factor) || out.factor == 0.0) {
    throw OptionError(fmt::format("{}: the factor is {} (not a finite non-zero number)", option, out.factor));
  }
  return out;
}

}  // namespace

ColumnExpression ParseColumnExpression(const std::string& option, const std::string& text,
                                       const std::function<bool(const std::string&)>& is_column,
                                       const std::function<std::optional<double>(const std::string&)>& scalar) {
  ColumnExpression out;
  out.text = text;
  std::string whole = Trimmed(text);
  if (whole.empty()) throw OptionError(fmt::format("{}: empty expression", option));
  // Derived-signal functions around the whole expression (unless a column
  // is named so), outermost first in the text.
  for (bool unwrapped = true; unwrapped && !is_column(whole);) {
    unwrapped = false;
    for (const char* name : {"integral", "derivative", "detrend"}) {
      const std::string head = std::string(name) + "(";
      if (whole.rfind(head, 0) != 0 || whole.back() != ')') continue;
      // The opening parenthesis must close at the very end.
      int depth = 0;
      std::size_t close = std::string::npos;
      for (std::size_t i = head.size() - 1; i < whole.size(); ++i) {
        if (whole[i] == '(') ++depth;
        if (whole[i] == ')' && --depth == 0) {
          close = i;
          break;
        }
      }
      if (close != whole.size() - 1) continue;
      out.operations.insert(out.operations.begin(), name);
      whole = Trimmed(whole.substr(head.size(), whole.size() - head.size() - 1));
      if (whole.empty()) throw OptionError(fmt::format("{}: {}() of nothing", option, name));
      if (out.operations.size() > 8) throw OptionError(fmt::format("{}: more than 8 nested functions", option));
      unwrapped = true;
      break;
    }
  }
  if (is_column(whole)) {
    out.reference = whole;
    out.terms.push_back({whole, 1.0});
    return out;
  }
  // A sum or difference of scaled columns (a coupled wrist's joint angle,
  // q6 = #6/32 - #5/45): split at '+' and '-' outside parentheses that are
  // not a sign (first, or after an operator) nor an exponent's (1e-3).
  std::vector<std::pair<double, std::string>> terms;
  {
    double sign = 1.0;
    int depth = 0;
    std::string current;
    for (std::size_t i = 0; i < whole.size(); ++i) {
      const char c = whole[i];
      if (c == '(') ++depth;
      if (c == ')') --depth;
      const std::string before = Trimmed(current);
      const bool exponent = !before.empty() && (before.back() == 'e' || before.back() == 'E') && before.size() >= 2 &&
                            (std::isdigit(static_cast<unsigned char>(before[before.size() - 2])) ||
                             before[before.size() - 2] == '.');
      const bool after_operator = before.empty() || before.back() == '*' || before.back() == '/';
      if (depth == 0 && (c == '+' || c == '-') && !after_operator && !exponent) {
        terms.emplace_back(sign, before);
        sign = c == '-' ? -1.0 : 1.0;
        current.clear();
      } else {
        current += c;
      }
    }
    terms.emplace_back(sign, Trimmed(current));
  }
  if (terms.size() > kMaxColumnTerms) {
    throw OptionError(fmt::format("{}: more than {} terms", option, kMaxColumnTerms));
  }
  for (auto [sign, term] : terms) {
    // A leading sign of the first term ("-#2 + #3").
    if (!term.empty() && (term[0] == '-' || term[0] == '+') && !is_column(term)) {
      if (term[0] == '-') sign = -sign;
      term = Trimmed(term.substr(1));
    }
    ColumnTerm t = ParseTerm(option, term, is_column, scalar, true);
    t.factor *= sign;
    if (t.reference.empty()) {
      out.offset += t.factor;
      continue;
    }
    for (const ColumnTerm& other : out.terms) {
      if (other.reference == t.reference) {
        throw OptionError(fmt::format("{}: the column '{}' appears twice; combine its factors", option, t.reference));
      }
    }
    out.terms.push_back(t);
  }
  if (out.terms.empty()) {
    throw OptionError(fmt::format("{}: no column in the expression (a constant column is not a log)", option));
  }
  if (!std::isfinite(out.offset)) throw OptionError(fmt::format("{}: the constants' sum is not finite", option));
  out.reference = out.terms.front().reference;
  out.factor = out.terms.front().factor;
  return out;
}

void ApplyColumnOperation(const std::string& operation, const std::vector<double>& time, std::vector<double>& values) {
  const std::size_t n = values.size();
  if (n == 0) return;
  if (operation == "integral") {
    double sum = 0.0, previous = values[0];
    values[0] = 0.0;
    for (std::size_t i = 1; i < n; ++i) {
      const double current = values[i];
      sum += 0.5 * (current + previous) * (time[i] - time[i - 1]);
      previous = current;
      values[i] = sum;
    }
  } else if (operation == "derivative") {
    if (n < 2) {
      values[0] = 0.0;
      return;
    }
    std::vector<double> out(n);
    out[0] = (values[1] - values[0]) / (time[1] - time[0]);
    out[n - 1] = (values[n - 1] - values[n - 2]) / (time[n - 1] - time[n - 2]);
    for (std::size_t i = 1; i + 1 < n; ++i) out[i] = (values[i + 1] - values[i - 1]) / (time[i + 1] - time[i - 1]);
    values = std::move(out);
  } else if (operation == "detrend") {
    double mean = 0.0;
    for (double v : values) mean += v / static_cast<double>(n);
    for (double& v : values) v -= mean;
  }
}

}  // namespace driveid
