// The fit core's one memo (fit/core/point_memo.h): a point is held only when it
// is the same bit for bit, split between shared and own parameters.
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "fit/core/point_memo.h"

namespace driveid {
namespace {

TEST_CASE("PointMemo holds a point bit for bit: not a neighbour, not -0 for 0, a NaN as itself") {
  PointMemo memo;
  const std::vector<double> a{1.0, 0.0}, b{std::nan("")};
  CHECK_FALSE(memo.valid());
  CHECK_FALSE(memo.Holds(a.data(), a.size()));
  memo.Remember(a.data(), a.size(), b.data(), b.size());
  CHECK(memo.valid());
  CHECK(memo.Holds(a.data(), a.size(), b.data(), b.size()));  // NaN compared by its bits
  // The same values split differently between the shared and own parts are
  // the same point; a shorter point is not.
  const std::vector<double> all{1.0, 0.0, b[0]}, front{1.0};
  const std::vector<double> back{0.0, b[0]};
  CHECK(memo.Holds(all.data(), all.size()));
  CHECK(memo.Holds(front.data(), front.size(), back.data(), back.size()));
  CHECK_FALSE(memo.Holds(a.data(), a.size()));
  const std::vector<double> negative_zero{1.0, -0.0}, next{std::nextafter(1.0, 2.0), 0.0};
  CHECK_FALSE(memo.Holds(negative_zero.data(), 2, b.data(), 1));
  CHECK_FALSE(memo.Holds(next.data(), 2, b.data(), 1));
  memo.Forget();
  CHECK_FALSE(memo.Holds(a.data(), a.size(), b.data(), b.size()));
  // An empty point (a block without parameters) is a point too.
  memo.Remember(nullptr, 0);
  CHECK(memo.Holds(nullptr, 0));
  CHECK_FALSE(memo.Holds(a.data(), 1));
}

}  // namespace
}  // namespace driveid
