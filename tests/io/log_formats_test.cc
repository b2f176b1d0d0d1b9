// io/axis_log.h, io/step_log.h, io/cdrive_log.h: each log written by its
// formatter reads back through its parser to the values it held (to the
// written digits), comments first; optional columns read when logged; a current is read as a torque with k_t,
// and refused without one, naming the file.
#include <cmath>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "io/axis_log.h"
#include "io/cdrive_log.h"
#include "io/step_log.h"

using namespace driveid;

namespace {

std::vector<double> Ramp(std::size_t n, double start, double step) {
  std::vector<double> v;
  for (std::size_t k = 0; k < n; ++k) v.push_back(start + step * static_cast<double>(k) + 1e-3 * std::sin(k));
  return v;
}

void CheckClose(const std::vector<double>& a, const std::vector<double>& b) {
  REQUIRE(a.size() == b.size());
  for (std::size_t k = 0; k < a.size(); ++k) CHECK(a[k] == Approx(b[k]).epsilon(1e-6).margin(1e-9));
}

}  // namespace

TEST_CASE("axis log: formatted, read back; a current times k_t, refused without it") {
  AxisLog log;
  log.path = "a.csv";
  log.time = Ramp(30, 0.0, 0.01);
  log.position = Ramp(30, 0.1, 0.02);
  log.force = Ramp(30, -1.0, 0.1);
  const std::string text = FormatAxisLog(log, {"made by a test", "truth: none"});
  CHECK(text.rfind("# made by a test\n# truth: none\n", 0) == 0);
  const AxisLog back = ParseAxisLog("a.csv", text, {}, 0.0);
  CheckClose(back.time, log.time);
  CheckClose(back.position, log.position);
  CheckClose(back.force, log.force);
  CHECK(back.rate.empty());
  const std::string current = "t,q,i\n0,0,1\n0.1,0.1,2\n0.2,0.2,3\n";
  CheckClose(ParseAxisLog("c.csv", current, {}, 0.5).force, {0.5, 1.0, 1.5});
  CHECK_THROWS_WITH(ParseAxisLog("c.csv", current, {}, 0.0), Catch::Contains("c.csv"));
}

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
