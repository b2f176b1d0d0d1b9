// sim/motion_program.h: eq. (32)'s s(x) = -20 x^7 + 70 x^6 - 84 x^5 + 35 x^4
// reaches the amplitude in one stroke with zero rate and acceleration at
// both ends, its rate and acceleration are the finite differences of its
// angle, the way back retraces it, and Table II's programs are by name.
#include "sim/motion_program.h"

#include <cmath>

#include <catch2/catch.hpp>

#include "core/errors.h"

using namespace driveid;

TEST_CASE("motion program: ends at rest, derivatives by finite differences, back along the same path") {
  const double amplitude = 20.0, stroke = 1.5;
  const ReferenceSample start = CalcProgramReference(amplitude, stroke, 0.0);
  const ReferenceSample end = CalcProgramReference(amplitude, stroke, stroke);
  CHECK(start.angle == 0.0);
  CHECK(start.rate == 0.0);
  CHECK(start.acceleration == 0.0);
  CHECK(end.angle == Approx(amplitude));
  CHECK(end.rate == Approx(0.0).margin(1e-9));
  CHECK(end.acceleration == Approx(0.0).margin(1e-9));
  // Half way: s(1/2) = 1/2 and the rate's peak 35/16 amplitude / stroke.
  const ReferenceSample middle = CalcProgramReference(amplitude, stroke, 0.5 * stroke);
  CHECK(middle.angle == Approx(0.5 * amplitude));
  CHECK(middle.rate == Approx(35.0 / 16.0 * amplitude / stroke));
  const double h = 1e-5;
  for (const double t : {0.1, 0.4, 0.77, 1.2, 1.9, 2.6}) {
    INFO("t = " << t);
    const ReferenceSample before = CalcProgramReference(amplitude, stroke, t - h);
    const ReferenceSample at = CalcProgramReference(amplitude, stroke, t);
    const ReferenceSample after = CalcProgramReference(amplitude, stroke, t + h);
    CHECK(at.rate == Approx((after.angle - before.angle) / (2.0 * h)).epsilon(1e-6));
    CHECK(at.acceleration == Approx((after.rate - before.rate) / (2.0 * h)).epsilon(1e-5).margin(1e-6));
    // The way back at 2 T - t retraces the angle with the rate reversed.
    const ReferenceSample back = CalcProgramReference(amplitude, stroke, 2.0 * stroke - t);
    if (t < stroke) {
      CHECK(back.angle == Approx(at.angle));
      CHECK(back.rate == Approx(-at.rate));
    }
  }
}

TEST_CASE("Table II programs by name; another name refused") {
  const MotionProgram helical = TableTwoProgram("helical", 2.0);
  CHECK(helical.amplitude_left == 14.0);
  CHECK(helical.amplitude_right == -28.0);
  CHECK(helical.stroke == 2.0);
  CHECK(TableTwoProgram("translation", 1.0).amplitude_right == -20.0);
  CHECK(TableTwoProgram("rotation", 1.0).amplitude_right == 20.0);
  CHECK_THROWS_AS(TableTwoProgram("circle", 1.0), OptionError);
}
