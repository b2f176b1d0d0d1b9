#include "sim/motion_program.h"

#include <cmath>
#include <stdexcept>

#include "core/errors.h"

namespace driveid {

MotionProgram TableTwoProgram(const std::string& name, double stroke) {
  if (name == "translation") return {name, 20.0, -20.0, stroke};
  if (name == "rotation") return {name, 20.0, 20.0, stroke};
  if (name == "helical") return {name, 14.0, -28.0, stroke};
  throw OptionError("‹program› " + name + ": choose translation, rotation or helical");
}

ReferenceSample CalcProgramReference(double amplitude, double stroke, double time) {
  double phase = std::fmod(time, 2.0 * stroke) / stroke;  // 0..2
  double direction = 1.0;
  if (phase > 1.0) {  // back along the same program
    phase = 2.0 - phase;
    direction = -1.0;
  }
  const double x = phase;
  const double s = x * x * x * x * (35.0 + x * (-84.0 + x * (70.0 - 20.0 * x)));
  const double ds = x * x * x * (140.0 + x * (-420.0 + x * (420.0 - 140.0 * x)));
  const double dds = x * x * (420.0 + x * (-1680.0 + x * (2100.0 - 840.0 * x)));
  return {amplitude * s, amplitude * ds * direction / stroke, amplitude * dds / (stroke * stroke)};
}

}  // namespace driveid
