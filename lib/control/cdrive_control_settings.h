// Settings of the C-drive position controller and friction compensation
// (seed 001 sections IV.C-D, eq. 31; SPEC 5.4), as a controller loads them
// from the parameter file's `cdrive.control` section.
#pragma once

namespace driveid {

/// How to read the seed's second gain K_I (printed unit "N m/rad s"):
/// PI  - tau = K_P e + K_I integral(e dt)          (K_I in N m/(rad s))
/// PD  - tau = K_P e + K_I de/dt                   (K_I read as a D gain, N m s/rad)
/// PID - tau = K_P e + K_I integral(e dt) + K_D de/dt
enum class ControlLaw { kPI, kPD, kPID };

const char* ControlLawName(ControlLaw law);

struct CDriveControlSettings {
  double proportional_gain = 7.17;   ///< K_P [N m/rad]
  double second_gain = 0.0239;       ///< K_I as printed; meaning set by `law`
  double derivative_gain = 0.0;      ///< K_D [N m s/rad], PID only
  ControlLaw law = ControlLaw::kPI;
  double dead_zone = 0.5;            ///< DZ half-width on velocities and velocity differences [rad/s]
  double rate_limit = 50.0;          ///< RL on each unit Coulomb term sgn(.) [1/s]
  double velocity_window = 0.01;     ///< backward-difference window of the encoder velocity [s]
  double sample_time = 0.001;        ///< controller period [s] (seed: 1 kHz)
  double encoder_counts = 8192.0;    ///< counts per motor revolution (seed: 13-bit)
};

}  // namespace driveid
