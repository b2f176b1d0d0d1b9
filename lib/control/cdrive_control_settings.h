// Settings of the C-drive position controller and friction compensation
// (seed 001 sections IV.C-D, eq. 31; docs/models.md#c-drive), as a controller loads them
// from the parameter file's `cdrive.control` section.
#pragma once

#include <optional>
#include <string>

#include "models/parameter_table.h"

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
  /// Finite gains, dead zone >= 0, rate limit, windows, period and counts > 0,
  /// and a velocity window of at least one period.
  bool IsValid(std::string* error) const;
};

/// The parameter file's `cdrive.control` section as written; what is not
/// given takes the defaults of CDriveControlSettings.
struct CDriveControlSection {
  static constexpr const char* kSectionName = "cdrive.control";
  std::optional<double> proportional_gain, second_gain, derivative_gain, dead_zone, rate_limit, velocity_window,
      sample_time, encoder_counts;
  std::optional<ControlLaw> law;
};

inline const ParameterTable<CDriveControlSection, CDriveControlSettings>& CDriveControlParameterTable() {
  using S = CDriveControlSection;
  using P = CDriveControlSettings;
  static const ParameterTable<S, P> table = {
      {Spec("K_P", "K_P", "N m/rad", "proportional gain").Required(), &S::proportional_gain,
       &P::proportional_gain},
      {Spec("K_I", "K_I", "N m/(rad s) or N m s/rad", "second gain as printed: integral (PI, PID) or derivative (PD)")
           .Required(),
       &S::second_gain, &P::second_gain},
      {Spec("K_D", "K_D", "N m s/rad", "derivative gain, PID only"),
       &S::derivative_gain, &P::derivative_gain},
      {Spec("dead_zone", "DZ", "rad/s", "dead zone on velocities and their difference"),
       &S::dead_zone, &P::dead_zone},
      {Spec("rate_limit", "RL", "1/s", "rate limit of each unit Coulomb term").Above(0.0),
       &S::rate_limit, &P::rate_limit},
      {Spec("velocity_window", "T_v", "s", "encoder velocity difference window").Above(0.0),
       &S::velocity_window, &P::velocity_window},
      {Spec("sample_time", "T_s", "s", "controller period").Above(0.0), &S::sample_time,
       &P::sample_time},
      {Spec("encoder_counts", "N_enc", "1/rev", "encoder counts per revolution").Above(0.0),
       &S::encoder_counts, &P::encoder_counts},
  };
  return table;
}

/// The controller settings of a section: given values over the defaults.
inline CDriveControlSettings MakeControlSettings(const CDriveControlSection& section) {
  CDriveControlSettings settings =
      MakeModelParameters(CDriveControlParameterTable(), section, CDriveControlSettings{}, "cdrive.control");
  if (section.law) settings.law = *section.law;
  return settings;
}

}  // namespace driveid
