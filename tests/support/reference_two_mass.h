// Independent generator of closed-loop two-mass joint logs for recovery
// tests of the frequency-response tools: written from the equations of
// motion alone (not from lib/), classic RK4 with sub-steps, a discrete PI
// speed loop on the measured motor speed and an excitation torque injected
// after the controller. Link side: J_m th_m'' = n tau - k (th_m - th_l)
// - d (th_m' - th_l') - b_m th_m',  J_l th_l'' = k (th_m - th_l) + d (...) - w,
// with w a random disturbance torque on the link. Logged in motor units:
// q_motor = n th_m, qd_motor = n th_m', tau, q_link = th_l, and the
// excitation r.
#pragma once

#include <cstdint>
#include <vector>

namespace driveid::testing {

struct TwoMassTruth {
  double gear_ratio = 10.0;
  double motor_inertia = 0.5, link_inertia = 1.5;  // link side [kg m^2]
  double stiffness = 2000.0, damping = 2.0;         // [N m/rad], [N m s/rad]
  double motor_viscous = 6.0;                       // link side [N m s/rad]
};

enum class Excitation { kMultisine, kNoise };

struct TwoMassExperiment {
  double rate = 1000.0;         // [Hz]
  double duration = 30.0;       // [s]
  double period = 2.0;          // multisine period [s]
  double f_min = 0.5, f_max = 50.0;  // multisine band [Hz]
  double amplitude = 0.3;       // excitation rms [N m, motor side]
  Excitation excitation = Excitation::kMultisine;
  double kp = 0.6, ki = 4.0;    // PI speed loop, motor side [N m s/rad], [N m/rad]
  double speed_noise = 0.05;    // std of the AR(1) speed-measurement noise [rad/s, motor]
  double speed_noise_ar = 0.8;
  double torque_noise = 0.002;  // white noise of the logged torque [N m]
  double disturbance = 0.5;     // std of the link disturbance torque [N m], AR(1) 0.99
  int substeps = 8;
  std::uint64_t seed = 1;
};

struct TwoMassLog {
  std::vector<double> t, tau, q_motor, qd_motor, q_link, r;
};

TwoMassLog SimulateTwoMassClosedLoop(const TwoMassTruth& truth, const TwoMassExperiment& experiment);

}  // namespace driveid::testing
