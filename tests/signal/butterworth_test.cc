// The zero-phase low-passes (signal/butterworth.h) against their closed-form
// responses: a sine's amplitude after filtfilt is |H| = 1 / (1 + (f/fc)^4)
// (the bilinear transform pre-warped at the cutoff, so exactly there and
// nearly elsewhere far below Nyquist), after the sharpened filter
// 3 |H|^2 - 2 |H|^3; a constant passes both unchanged.
#include "signal/butterworth.h"

#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

using namespace driveid;

namespace {

constexpr double kRate = 1000.0;

// The amplitude of a unit sine at `f` after `filter`, read in the middle
// of a 20 s record (clear of the ends) by projection on sin and cos.
template <typename Filter>
double Amplitude(double f, Filter filter) {
  std::vector<double> x(20000);
  for (std::size_t k = 0; k < x.size(); ++k) x[k] = std::sin(2.0 * M_PI * f * static_cast<double>(k) / kRate);
  const std::vector<double> y = filter(x);
  double s = 0.0, c = 0.0;
  const std::size_t from = 5000, count = 10000;  // whole periods for f in 1/10 s steps
  for (std::size_t k = from; k < from + count; ++k) {
    const double phase = 2.0 * M_PI * f * static_cast<double>(k) / kRate;
    s += y[k] * std::sin(phase);
    c += y[k] * std::cos(phase);
  }
  return 2.0 * std::hypot(s, c) / static_cast<double>(count);
}

double Warped(double f, double cutoff) {
  // The bilinear transform's frequency map, pre-warped at the cutoff.
  return std::tan(M_PI * f / kRate) / std::tan(M_PI * cutoff / kRate) * cutoff;
}

}  // namespace

TEST_CASE("filtfilt and its sharpened form have their closed-form amplitudes", "[signal]") {
  const double cutoff = 20.0;
  for (const double f : {2.0, 5.0, 10.0, 20.0, 30.0}) {
    const double h = 1.0 / (1.0 + std::pow(Warped(f, cutoff) / cutoff, 4));
    const double plain = Amplitude(f, [&](const std::vector<double>& x) { return ZeroPhaseLowPass(x, cutoff, kRate); });
    const double flat = Amplitude(f, [&](const std::vector<double>& x) { return FlatZeroPhaseLowPass(x, cutoff, kRate); });
    CHECK(plain == Approx(h).margin(1e-6));
    CHECK(flat == Approx(3.0 * h * h - 2.0 * h * h * h).margin(1e-6));
  }
  // Flat where it matters: at a quarter of the cutoff the sharpened filter
  // loses 5e-5 of the amplitude, the plain one 0.39 %.
  const double quarter = Amplitude(5.0, [&](const std::vector<double>& x) { return FlatZeroPhaseLowPass(x, cutoff, kRate); });
  CHECK(1.0 - quarter < 1e-4);
}

TEST_CASE("the sharpened filter keeps a constant and a ramp", "[signal]") {
  std::vector<double> x(3000);
  for (std::size_t k = 0; k < x.size(); ++k) x[k] = 2.5 + 0.01 * static_cast<double>(k);
  const std::vector<double> y = FlatZeroPhaseLowPass(x, 15.0, kRate);
  for (std::size_t k = 0; k < x.size(); ++k) REQUIRE(y[k] == Approx(x[k]).margin(1e-9));
}
