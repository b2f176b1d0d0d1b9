// io/axis_reference.h and io/torque_reference.h: a reference written and
// read back; a position-only reference gets its rate and acceleration by
// central differences (exact on a parabola); an excitation's rate from its
// constant step, and uneven steps or too few rows refused by file name.
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "io/axis_reference.h"
#include "io/torque_reference.h"

using namespace driveid;

namespace {

std::string Write(const std::string& name, const std::string& text) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / ("driveid_references_" + name);
  std::ofstream(path) << text;
  return path.string();
}

}  // namespace

TEST_CASE("axis reference: written and read back; a parabola's rate and acceleration by central differences") {
  AxisReference r;
  for (int k = 0; k < 50; ++k) {
    const double t = 0.01 * k;
    r.time.push_back(t);
    r.position.push_back(1.5 * t * t);
    r.rate.push_back(3.0 * t);
    r.acceleration.push_back(3.0);
  }
  const std::string path = Write("full.csv", FormatAxisReference(r, {"test"}));
  const AxisReference back = ReadAxisReference(path);
  REQUIRE(back.time.size() == r.time.size());
  for (std::size_t k = 0; k < r.time.size(); ++k) {
    CHECK(back.position[k] == Approx(r.position[k]).margin(1e-12));
    CHECK(back.rate[k] == Approx(r.rate[k]).margin(1e-12));
  }
  std::string positions = "t,q\n";
  for (std::size_t k = 0; k < r.time.size(); ++k) positions += std::to_string(r.time[k]) + "," +
                                                             std::to_string(r.position[k]) + "\n";
  const AxisReference derived = ReadAxisReference(Write("q.csv", positions));
  // Exact inside; the ends' one-sided rates reach the acceleration's first and last two samples.
  for (std::size_t k = 1; k + 1 < derived.time.size(); ++k) {
    CHECK(derived.rate[k] == Approx(3.0 * derived.time[k]).margin(1e-6));
    if (k >= 2 && k + 2 < derived.time.size()) CHECK(derived.acceleration[k] == Approx(3.0).epsilon(1e-3));
  }
  std::remove(path.c_str());
}

TEST_CASE("torque reference: the rate from its step; uneven steps and short files refused by name") {
  TorqueReference r;
  for (int k = 0; k < 40; ++k) {
    r.time.push_back(0.002 * k);
    r.torque.push_back(k % 3 - 1.0);
  }
  const std::string path = Write("tau.csv", FormatTorqueReference(r, {"test"}));
  const TorqueReference back = ReadTorqueReference(path);
  CHECK(TorqueReferenceRate(back) == Approx(500.0));
  CHECK(back.torque == r.torque);
  r.time[20] += 0.0007;
  const std::string uneven = Write("uneven.csv", FormatTorqueReference(r, {}));
  CHECK_THROWS_WITH(ReadTorqueReference(uneven), Catch::Contains(uneven));
  r.time.resize(5);
  r.torque.resize(5);
  const std::string short_file = Write("short.csv", FormatTorqueReference(r, {}));
  CHECK_THROWS_AS(ReadTorqueReference(short_file), InputError);
}
