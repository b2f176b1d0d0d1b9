// Motion programs of seed 001 (docs/models.md#motion-programs): each motor follows
//   psi_I(t) = alpha_I s(t/T),  s(x) = -20 x^7 + 70 x^6 - 84 x^5 + 35 x^4  (eq. 32)
// forward over one stroke T, then back along the same program (period 2 T;
// the seed runs T = 1 s, 0.5 Hz). s has zero rate, acceleration and jerk at
// both ends. Table II amplitudes: translation (20, -20) rad, rotation
// (20, 20), helical (14, -28) (pitch 180 mm).
#pragma once

#include <string>

namespace driveid {

struct MotionProgram {
  std::string name;
  double amplitude_left = 0.0;   ///< alpha_L [rad]
  double amplitude_right = 0.0;  ///< alpha_R [rad]
  double stroke = 1.0;           ///< T [s]
};

/// Table II program by name (translation, rotation, helical); throws
/// OptionError for another name.
MotionProgram TableTwoProgram(const std::string& name, double stroke);

/// Reference of one motor at time t >= 0: angle [rad], rate, acceleration.
struct ReferenceSample {
  double angle, rate, acceleration;
};
ReferenceSample CalcProgramReference(double amplitude, double stroke, double time);

}  // namespace driveid
