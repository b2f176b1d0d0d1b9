// Column expressions of `--col NAME=EXPR` (docs/formats.md#column-expressions):
// a source column times or divided by constant factors, e.g. `10*#14`,
// `pi/180*pos_deg`, `pos/32`, `gtau*vir` (gtau a scalar of the MAT file).
// A factor is a number, `pi`, a scalar of the source, or the one column
// reference: a header name, a 1-based position `#k`, or a MAT variable path
// (`rec.pos(1,:)`). The column may not be a divisor. Terms of this kind
// may be added and subtracted (`#6/32 - #5/45`, each column once), and so
// may constants (`#2/32 - pi/2`: an encoder zero that is not the model's,
// as an MDH offset), so long as one term holds a column. The whole may be
// wrapped in derived-signal functions (applied innermost first, over the
// log's time base, after crops): `integral(EXPR)` (cumulative trapezoid, 0
// at the first sample), `derivative(EXPR)` (central differences, one-sided
// at the ends), `detrend(EXPR)` (mean removed), e.g. `integral(10*#2)`.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace driveid {

/// One term of a sum: a source column and the constant it is multiplied by.
struct ColumnTerm {
  std::string reference;
  double factor = 1.0;
};
inline constexpr std::size_t kMaxColumnTerms = 8;

struct ColumnExpression {
  std::string text;       ///< as given (recorded in the provenance)
  std::string reference;  ///< the first term's source column
  double factor = 1.0;    ///< the first term's factor
  /// Every term, the first included: the column is their sum (a coupled
  /// wrist: `#6/32 - #5/45`), at most kMaxColumnTerms.
  std::vector<ColumnTerm> terms;
  /// The constant terms' sum, added to the column's (`- pi/2` of `#2/32 - pi/2`).
  double offset = 0.0;
  /// Derived-signal functions, innermost first: "integral", "derivative", "detrend".
  std::vector<std::string> operations;
};

/// Applies `operation` (one of ColumnExpression::operations) to `values`
/// sampled at `time` (strictly increasing, same length).
void ApplyColumnOperation(const std::string& operation, const std::vector<double>& time, std::vector<double>& values);

/// Parses EXPR. `is_column(word)` tells whether a word names a column of
/// the source (checked first, so that a header containing '*' or '/' can be
/// named whole); `scalar(word)` gives a named constant of the source. Throws
/// OptionError naming `option` ("--col tau=...") on a malformed expression,
/// no column reference, two in one product, a column divisor, or a zero divisor.
ColumnExpression ParseColumnExpression(const std::string& option, const std::string& text,
                                       const std::function<bool(const std::string&)>& is_column,
                                       const std::function<std::optional<double>(const std::string&)>& scalar);

}  // namespace driveid
