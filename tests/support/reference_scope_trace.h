// Independent generator of a servo drive's scope trace of an elastic axis
// (written from the equations of motion alone, not from lib/): a cascade
// controller at the drive's rate — position P on the motor encoder, speed PI
// on the encoder's difference quotient through a first-order filter, the
// torque applied one sample late — running point-to-point moves (trapezoid
// speed profiles with dwells, alternating direction). Plant, link side:
//   J_m th_m'' = n tau - k D - d D' - b_m th_m' - c_m tanh(th_m' / v_c),
//   J_l th_l'' = k D + d D' - b_l th_l',  D = th_m - th_l,
// integrated by RK4 with sub-steps. Logged as the drive's scope writes it:
// time in ms, raw encoder counts (motor and link), and the torque in
// tenths of a percent of the rated torque, with white noise on the torque
// (as a current-based torque reads).
#pragma once

#include <cstdint>
#include <string>

namespace driveid::testing {

struct ScopeAxis {
  double gear_ratio = 1.0;
  double motor_inertia = 0.02, link_inertia = 0.1;  // link side [kg m^2]
  double stiffness = 2000.0, damping = 0.5;          // [N m/rad], [N m s/rad]
  double motor_viscous = 0.1, motor_coulomb = 0.3;   // [N m s/rad], [N m]
  double coulomb_speed = 0.002;                      // v_c [rad/s] of the tanh
  double link_viscous = 0.05;                        // [N m s/rad]
};

struct ScopeSettings {
  double rate = 4000.0;              // [Hz]
  double duration = 6.0;             // [s]
  double move = 1.0;                 // stroke of a move [rad, motor]
  double max_speed = 8.0;            // [rad/s, motor]
  double acceleration = 400.0;       // [rad/s^2, motor]
  double dwell = 0.15;               // [s] between moves
  double kp_position = 10.0;         // [1/s]
  double kp_speed = 4.0, ki_speed = 40.0;  // [N m s/rad], [N m/rad], motor shaft
  double speed_filter_hz = 800.0;
  double rated_torque = 10.0;        // [N m, motor shaft]: 100 %
  double torque_noise = 0.02;        // [N m] std, white
  double motor_counts = 1 << 17, link_counts = 1 << 20;  // per revolution
  int substeps = 20;
  std::uint64_t seed = 1;
};

/// CSV text: header `time_ms,enc_motor,enc_link,torque_permille`, one row per sample.
std::string SimulateScopeTrace(const ScopeAxis& axis, const ScopeSettings& settings);

}  // namespace driveid::testing
