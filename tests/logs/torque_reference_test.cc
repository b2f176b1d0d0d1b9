// logs/torque_reference.h: an excitation's rate from its constant step;
// uneven steps or too few rows refused by file name.
#include <cstdio>
#include <filesystem>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "support/log_values.h"
#include "logs/torque_reference.h"

using namespace driveid;

using driveid::testing::WriteTemporary;

TEST_CASE("torque reference: the rate from its step; uneven steps and short files refused by name") {
  TorqueReference r;
  for (int k = 0; k < 40; ++k) {
    r.time.push_back(0.002 * k);
    r.torque.push_back(k % 3 - 1.0);
  }
  const std::string path = WriteTemporary("tau.csv", FormatTorqueReference(r, {"test"}));
  const TorqueReference back = ReadTorqueReference(path);
  CHECK(TorqueReferenceRate(back) == Approx(500.0));
  CHECK(back.torque == r.torque);
  r.time[20] += 0.0007;
  const std::string uneven = WriteTemporary("uneven.csv", FormatTorqueReference(r, {}));
  CHECK_THROWS_WITH(ReadTorqueReference(uneven), Catch::Contains(uneven));
  r.time.resize(5);
  r.torque.resize(5);
  const std::string short_file = WriteTemporary("short.csv", FormatTorqueReference(r, {}));
  CHECK_THROWS_AS(ReadTorqueReference(short_file), InputError);
}
