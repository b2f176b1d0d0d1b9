// logs/cdrive_log.h: a C-drive log written by its formatter reads back to its
// values; currents are read as torques with k_t, refused without one.
#include <catch2/catch.hpp>

#include "core/errors.h"
#include "logs/cdrive_log.h"
#include "support/log_values.h"

using namespace driveid;
using driveid::testing::CheckClose;
using driveid::testing::Ramp;

TEST_CASE("C-drive log: formatted, read back; currents with k_t") {
  CDriveLog log;
  log.path = "c.csv";
  log.time = Ramp(8, 0.0, 0.002);
  log.angle_left = Ramp(8, 0.0, 0.5);
  log.angle_right = Ramp(8, 0.0, -0.5);
  log.torque_left = Ramp(8, 0.1, 0.01);
  log.torque_right = Ramp(8, -0.1, 0.02);
  const CDriveLog back = ParseCDriveLog("c.csv", FormatCDriveLog(log, {"cdrive"}), {}, 0.0);
  CheckClose(back.angle_left, log.angle_left);
  CheckClose(back.angle_right, log.angle_right);
  CheckClose(back.torque_left, log.torque_left);
  CheckClose(back.torque_right, log.torque_right);
  const std::string currents = "t,psi_L,psi_R,i_L,i_R\n0,0,0,1,2\n0.1,1,1,3,4\n0.2,2,2,5,6\n0.3,3,3,7,8\n0.4,4,4,9,10\n";
  CheckClose(ParseCDriveLog("i.csv", currents, {}, 0.1).torque_right, {0.2, 0.4, 0.6, 0.8, 1.0});
  CHECK_THROWS_AS(ParseCDriveLog("i.csv", currents, {}, 0.0), InputError);
}
