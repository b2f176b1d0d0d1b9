// What a read resonance must be (fit/frf/response_features.h): a maximum of |H|
// whose phase turns down by 90 degrees or more, inside the band and a bin
// away from 0.8 x Nyquist. Responses written here from their closed forms
// (a rigid joint behind a delay, a lead corner, a filter's edge) and a
// drifting position read per period from the independent closed-loop
// generator (tests/support/reference_two_mass.cc).
#include <cmath>
#include <complex>
#include <random>

#include <catch2/catch.hpp>

#include "fit/frf/response_features.h"
#include "signal/frequency_response.h"
#include "support/reference_two_mass.h"

using namespace driveid;
using Complex = std::complex<double>;

namespace {

// H_rate = shape(s) on `bins` linear bins over (0, top] Hz with 3 %
// magnitude and 2 degree phase noise and their std.
ResponseData Noisy(const std::function<Complex(Complex)>& shape, double top, int bins, double nyquist, unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> unit;
  ResponseData d;
  for (int i = 1; i <= bins; ++i) {
    const double f = top * i / bins;
    d.frequency.push_back(f);
    d.response.push_back(shape(Complex(0.0, 2.0 * M_PI * f)) * std::exp(0.03 * unit(random)) *
                         std::exp(Complex(0.0, 2.0 * M_PI / 180.0 * unit(random))));
    d.log_magnitude_std.push_back(0.03);
    d.phase_std.push_back(2.0 * M_PI / 180.0);
  }
  d.nyquist_hz = nyquist;
  return d;
}

}  // namespace

TEST_CASE("a rigid joint behind a delay has no resonance to read") {
  // n^2 s / (J s + b) e^(-s tau): flat in acceleration, no mode in 0 .. 80 Hz.
  for (unsigned seed = 1; seed <= 10; ++seed) {
    const ResponseData d = Noisy([](Complex s) { return 100.0 * s / (2.0 * s + 6.0) * std::exp(-s * 0.002); }, 80.0,
                                 160, 500.0, seed);
    const ResponseFeatures read = ReadResponseFeatures(d, ResponseQuantity::kRate, {});
    INFO("seed " << seed << ": resonance " << read.resonance.value << ", anti-resonance " << read.antiresonance.value);
    CHECK(read.resonance.value == 0.0);
    CHECK(read.antiresonance.value == 0.0);
    CHECK_FALSE(read.warnings.empty());
  }
}

TEST_CASE("a maximum at a filter's edge or at 0.8 x Nyquist is not a resonance") {
  // A lead whose |H_acc| rises to the top of the band (phase up, not down),
  // and a drive whose sampled response peaks near 0.8 x Nyquist (125 Hz):
  // a second-order rise with no phase fall, then the anti-aliasing roll-off.
  const auto lead = [](Complex s) { return 100.0 * s / (2.0 * s + 6.0) * (1.0 + s / 200.0) / (1.0 + s / 2000.0); };
  const auto edge = [](Complex s) {
    const Complex w = s / (2.0 * M_PI * 100.0);
    return 100.0 * s / (2.0 * s + 6.0) * (1.0 + w * w * 0.8) / (1.0 + 0.2 * w + w * w * 0.2);
  };
  for (const auto& shape : {std::function<Complex(Complex)>(lead), std::function<Complex(Complex)>(edge)}) {
    const ResponseData d = Noisy(shape, 124.0, 248, 125.0, 3);
    const ResponseFeatures read = ReadResponseFeatures(d, ResponseQuantity::kRate, {});
    INFO("resonance " << read.resonance.value);
    CHECK(read.resonance.value == 0.0);
  }
}

TEST_CASE("a true resonance still reads, its phase turning") {
  // The two-mass rate response (link side J_m 0.5, J_l 1.5, k 2000, d 2,
  // b_m 6, n 10): modes at 11.62 and 5.81 Hz.
  const auto joint = [](Complex s) {
    const Complex al = 1.5 * s * s + 2.0 * s + 2000.0, am = 0.5 * s * s + 8.0 * s + 2000.0;
    return 100.0 * s * al / (am * al - (2.0 * s + 2000.0) * (2.0 * s + 2000.0));
  };
  const ResponseData d = Noisy(joint, 50.0, 400, 500.0, 5);
  const ResponseFeatures read = ReadResponseFeatures(d, ResponseQuantity::kRate, {});
  const double fr = std::sqrt(2000.0 * (1 / 0.5 + 1 / 1.5)) / (2 * M_PI), fa = std::sqrt(2000.0 / 1.5) / (2 * M_PI);
  CHECK(std::abs(read.resonance.value / fr - 1.0) < 0.02);
  CHECK(std::abs(read.antiresonance.value / fa - 1.0) < 0.02);
}

TEST_CASE("a drifting position read per period gives the modes of the rate") {
  using namespace driveid::testing;
  const TwoMassTruth truth;
  TwoMassExperiment e;
  TwoMassLog log = SimulateTwoMassClosedLoop(truth, e);
  // The joint turning at 0.5 rad/s (link side) on top of the excitation: a
  // rigid-body motion of both masses, which a linear joint superposes.
  for (std::size_t k = 0; k < log.t.size(); ++k) log.q_motor[k] += truth.gear_ratio * 0.5 * log.t[k];
  FrequencyResponseOptions options;
  const FrequencyResponse frf = EstimateFrequencyResponse({{log.tau, log.q_motor, log.r}}, e.rate, options);
  REQUIRE(frf.method == FrequencyMethod::kPeriodic);
  const ResponseData d{frf.frequency, frf.response, frf.coherence, frf.log_magnitude_std, frf.phase_std,
                       frf.excitation, 0.5 * e.rate, 0.0};
  const ResponseFeatures read = ReadResponseFeatures(d, ResponseQuantity::kPosition, {});
  const double fr = std::sqrt(2000.0 * (1 / 0.5 + 1 / 1.5)) / (2 * M_PI), fa = std::sqrt(2000.0 / 1.5) / (2 * M_PI);
  INFO("resonance " << read.resonance.value << " +- " << read.resonance.standard_error << ", anti-resonance "
                    << read.antiresonance.value << " +- " << read.antiresonance.standard_error);
  CHECK(std::abs(read.resonance.value - fr) < 3.0 * read.resonance.standard_error + 0.01 * fr);
  CHECK(std::abs(read.antiresonance.value - fa) < 3.0 * read.antiresonance.standard_error + 0.01 * fa);
}
