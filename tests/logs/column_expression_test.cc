// logs/column_expression.h and logs/transpose_table.h: a column times and
// divided by factors (pi, a scalar of the source), functions innermost
// first, refusals named; integral, derivative and detrend against closed
// forms; a table of rows turned into columns.
#include "logs/column_expression.h"

#include <cmath>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "logs/transpose_table.h"

using namespace driveid;

namespace {

bool IsColumn(const std::string& word) { return word == "pos" || word == "#3" || word == "a*b"; }
std::optional<double> Scalar(const std::string& word) {
  return word == "gain" ? std::optional<double>(2.5) : std::nullopt;
}

}  // namespace

TEST_CASE("column expressions: factors, functions, refusals") {
  const ColumnExpression e = ParseColumnExpression("--col q=...", "pi/180*pos", IsColumn, Scalar);
  CHECK(e.reference == "pos");
  CHECK(e.factor == Approx(M_PI / 180.0));
  const ColumnExpression s = ParseColumnExpression("--col q=...", "gain*#3/4", IsColumn, Scalar);
  CHECK(s.reference == "#3");
  CHECK(s.factor == Approx(2.5 / 4.0));
  // A header holding '*' is named whole.
  CHECK(ParseColumnExpression("--col q=...", "a*b", IsColumn, Scalar).reference == "a*b");
  const ColumnExpression f = ParseColumnExpression("--col q=...", "detrend(integral(10*pos))", IsColumn, Scalar);
  CHECK(f.factor == Approx(10.0));
  CHECK(f.operations == std::vector<std::string>{"integral", "detrend"});
  CHECK_THROWS_AS(ParseColumnExpression("--col q=...", "pos/0", IsColumn, Scalar), OptionError);
  CHECK_THROWS_AS(ParseColumnExpression("--col q=...", "2/pos", IsColumn, Scalar), OptionError);
  CHECK_THROWS_AS(ParseColumnExpression("--col q=...", "pos*#3", IsColumn, Scalar), OptionError);
  CHECK_THROWS_AS(ParseColumnExpression("--col q=...", "3*4", IsColumn, Scalar), OptionError);
  // Constant terms of a sum go into the offset; at least one term holds a column.
  const ColumnExpression o = ParseColumnExpression("--col q=...", "-pi/2 + pos/32 + gain", IsColumn, Scalar);
  CHECK(o.reference == "pos");
  CHECK(o.factor == Approx(1.0 / 32));
  CHECK(o.offset == Approx(2.5 - M_PI / 2));
  CHECK(o.terms.size() == 1);
  CHECK(ParseColumnExpression("--col q=...", "pos", IsColumn, Scalar).offset == 0.0);
  CHECK_THROWS_WITH(ParseColumnExpression("--col q=...", "1 - pi", IsColumn, Scalar), Catch::Contains("no column"));
  CHECK_THROWS_WITH(ParseColumnExpression("--col q=...", "pos + 1e308*10", IsColumn, Scalar), Catch::Contains("not a finite"));
}

TEST_CASE("column operations: integral, derivative and detrend of a ramp against closed forms") {
  std::vector<double> time, ramp;
  for (int k = 0; k <= 100; ++k) {
    time.push_back(0.01 * k);
    ramp.push_back(2.0 * 0.01 * k);  // 2 t
  }
  std::vector<double> integral = ramp;
  ApplyColumnOperation("integral", time, integral);
  for (std::size_t k = 0; k < time.size(); ++k) CHECK(integral[k] == Approx(time[k] * time[k]).margin(1e-12));
  std::vector<double> derivative = ramp;
  ApplyColumnOperation("derivative", time, derivative);
  for (double d : derivative) CHECK(d == Approx(2.0));
  std::vector<double> detrended = ramp;
  ApplyColumnOperation("detrend", time, detrended);
  double mean = 0.0;
  for (double v : detrended) mean += v / static_cast<double>(detrended.size());
  CHECK(mean == Approx(0.0).margin(1e-12));
  CHECK(detrended.back() - detrended.front() == Approx(2.0));  // the mean removed, not the slope
}

TEST_CASE("transpose: rows become columns, named rows a header, a short row refused") {
  CHECK(TransposeTable("b.txt", "# bode\nfrequency,1,2,3\nmagnitude,4,5,6\n\n") ==
        "# bode\nfrequency,magnitude\n1,4\n2,5\n3,6\n");
  CHECK(TransposeTable("b.txt", "1;2\n3;4\n") == "1,3\n2,4\n");
  CHECK_THROWS_AS(TransposeTable("b.txt", "1,2,3\n4,5\n"), InputError);
}
