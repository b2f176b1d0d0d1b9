// logs/step_log.h: a step log written by its formatter reads back to its values;
// the optional angles are read when logged.
#include <catch2/catch.hpp>

#include "core/errors.h"
#include "logs/step_log.h"
#include "support/log_values.h"

using namespace driveid;
using driveid::testing::CheckClose;
using driveid::testing::Ramp;

TEST_CASE("step log: formatted and read back; the optional angles read when logged") {
  StepLog log;
  log.path = "s.csv";
  log.time = Ramp(12, 0.0, 0.001);
  log.motor_torque = Ramp(12, -0.8, 0.0);
  log.link_torque = Ramp(12, 2.0, -0.1);
  const StepLog back = ParseStepLog("s.csv", FormatStepLog(log, {"step"}));
  CheckClose(back.time, log.time);
  CheckClose(back.motor_torque, log.motor_torque);
  CheckClose(back.link_torque, log.link_torque);
  CHECK(back.motor_angle.empty());
  const StepLog angles = ParseStepLog("a.csv", "t,tau_motor,tau_link,q_motor\n0,1,2,3\n0.1,1,2,4\n0.2,1,2,5\n");
  CheckClose(angles.motor_angle, {3.0, 4.0, 5.0});
  CHECK(angles.link_angle.empty());
}
