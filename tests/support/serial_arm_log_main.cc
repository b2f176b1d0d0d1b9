// Writes the reference three-joint arm (tests/support/reference_serial_arm.h)
// as a URDF and one of its logs as CSV (t, q_<joint>, tau_<joint>), for the
// command-line tests of `drivetrain-fit robot --urdf`.
// Usage: serial_arm_log ARM.urdf LOG.csv [seed [joints (3 or 6) [rate Hz [duration s]]]]
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "support/reference_arm_urdf.h"
#include "support/reference_serial_arm.h"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: serial_arm_log ARM.urdf LOG.csv [seed [joints [rate [duration]]]]\n");
    return 2;
  }
  const reference::Arm arm =
      argc > 4 && std::atoi(argv[4]) == 6 ? reference::SixJointArm() : reference::ThreeJointArm();
  std::ofstream urdf(argv[1]);
  urdf << reference::ArmUrdf(arm);
  reference::ArmLogOptions o;
  if (argc > 3) o.seed = static_cast<unsigned>(std::atoi(argv[3]));
  if (argc > 5) o.rate = std::atof(argv[5]);
  if (argc > 6) o.duration = std::atof(argv[6]);
  const reference::ArmLog log = reference::SimulateArm(arm, o);
  std::ofstream csv(argv[2]);
  csv.precision(10);
  csv << "t";
  for (const auto& j : arm.joints) csv << ",q_" << j.name << ",tau_" << j.name;
  csv << '\n';
  for (std::size_t k = 0; k < log.t.size(); ++k) {
    csv << log.t[k];
    for (std::size_t j = 0; j < arm.joints.size(); ++j) csv << ',' << log.q[j][k] << ',' << log.tau[j][k];
    csv << '\n';
  }
  return urdf && csv ? 0 : 1;
}
