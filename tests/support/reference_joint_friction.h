// Independent generator of closed-loop elastic-joint logs with motor
// Coulomb friction that sticks, for recovery tests of the output-error joint
// fit: written from the equations of motion alone (not from lib/), classic
// RK4 with many sub-steps per sample; a motor whose speed crosses zero within
// a sub-step is brought to zero at the crossing (linear interpolation) and
// held there while the torque on it stays within its Coulomb level
// (Karnopp). Link side: J_m th_m'' = n tau - k D - d D' - b_m th_m'
// - c_m sgn(th_m') - tau_0, J_l th_l'' = k D + d D' - b_l th_l', D = th_m - th_l.
// A discrete PI speed loop on the measured motor speed follows a slow
// reversing speed reference; a Schroeder multisine torque is injected after
// it. Logged: t, tau (motor shaft: the command as applied, plus AR(1)
// measurement noise when torque_noise > 0, as a current-based torque
// reads), q_motor = n th_m and q_link = th_l through quantising encoders
// plus AR(1) noise.
#pragma once

#include <cstdint>
#include <vector>

namespace driveid::testing {

struct FrictionJointTruth {
  double gear_ratio = 10.0;
  double motor_inertia = 0.5, link_inertia = 1.5;  // link side [kg m^2]
  double stiffness = 2000.0, damping = 2.0;         // [N m/rad], [N m s/rad]
  double motor_viscous = 6.0, motor_coulomb = 2.0;  // link side [N m s/rad], [N m]
  double link_viscous = 0.5;                        // [N m s/rad]
  double offset = 0.5;                              // tau_0, link side [N m]
  // What the two-mass model lacks (all 0: the model itself):
  double hardening = 0.0;  // k3 [N m/rad^3]: the spring is k D + k3 D^3
  double backlash = 0.0;   // total gap [rad]: the spring acts on D -+ gap/2 outside it, 0 inside
  double ripple = 0.0;     // torque ripple on the motor [N m, motor shaft], not in the logged torque
  int ripple_order = 6;    // its order of the motor's rotation: ripple sin(order q_motor)
};

struct FrictionJointExperiment {
  double rate = 1000.0;           // [Hz]
  double duration = 10.0;         // [s]
  double reference_speed = 10.0;  // amplitude of the motor-speed reference [rad/s, motor shaft]
  double reference_hz = 0.4;      // its frequency (a sine: reverses, so the motor sticks)
  double period = 1.0;            // multisine period [s]
  double f_min = 1.0, f_max = 40.0;  // multisine band [Hz]
  double amplitude = 0.4;         // excitation rms [N m, motor shaft]
  double kp = 0.3, ki = 3.0;      // PI speed loop, motor shaft [N m s/rad], [N m/rad]
  double motor_counts = 1 << 18, link_counts = 1 << 20;  // encoder counts per revolution
  double noise = 2e-5;            // std of the AR(1) angle noise [rad] (link noise: noise / n)
  double noise_ar = 0.7;
  double torque_noise = 0.0;      // std of the AR(1) noise on the logged torque [N m, motor shaft]
  double torque_noise_ar = 0.0;   // its lag-1 correlation (0: white)
  int substeps = 50;
  std::uint64_t seed = 1;
};

struct FrictionJointLog {
  std::vector<double> t, tau, q_motor, q_link;
  int sticks = 0;  // times the motor came to rest and stuck
};

FrictionJointLog SimulateFrictionJoint(const FrictionJointTruth& truth, const FrictionJointExperiment& experiment);

}  // namespace driveid::testing
