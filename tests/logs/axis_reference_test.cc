// logs/axis_reference.h: a reference written and read back; a position-only
// reference gets its rate and acceleration by central differences (exact on
// a parabola).
#include <cstdio>
#include <filesystem>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "support/log_values.h"
#include "logs/axis_reference.h"

using namespace driveid;

using driveid::testing::WriteTemporary;

TEST_CASE("axis reference: written and read back; a parabola's rate and acceleration by central differences") {
  AxisReference r;
  for (int k = 0; k < 50; ++k) {
    const double t = 0.01 * k;
    r.time.push_back(t);
    r.position.push_back(1.5 * t * t);
    r.rate.push_back(3.0 * t);
    r.acceleration.push_back(3.0);
  }
  const std::string path = WriteTemporary("full.csv", FormatAxisReference(r, {"test"}));
  const AxisReference back = ReadAxisReference(path);
  REQUIRE(back.time.size() == r.time.size());
  for (std::size_t k = 0; k < r.time.size(); ++k) {
    CHECK(back.position[k] == Approx(r.position[k]).margin(1e-12));
    CHECK(back.rate[k] == Approx(r.rate[k]).margin(1e-12));
  }
  std::string positions = "t,q\n";
  for (std::size_t k = 0; k < r.time.size(); ++k) positions += std::to_string(r.time[k]) + "," +
                                                             std::to_string(r.position[k]) + "\n";
  const AxisReference derived = ReadAxisReference(WriteTemporary("q.csv", positions));
  // Exact inside; the ends' one-sided rates reach the acceleration's first and last two samples.
  for (std::size_t k = 1; k + 1 < derived.time.size(); ++k) {
    CHECK(derived.rate[k] == Approx(3.0 * derived.time[k]).margin(1e-6));
    if (k >= 2 && k + 2 < derived.time.size()) CHECK(derived.acceleration[k] == Approx(3.0).epsilon(1e-3));
  }
  std::remove(path.c_str());
}
