// Frequency response and two-mass fit against an independent closed-loop
// generator (tests/support/reference_two_mass.cc), and the model's response
// against finite differences and its closed form.
#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "fit/frf/frequency_response_fit.h"
#include "fit/frf/response_features.h"
#include "signal/frequency_response.h"
#include "support/reference_two_mass.h"

using namespace driveid;
using driveid::testing::Excitation;
using driveid::testing::SimulateTwoMassClosedLoop;
using driveid::testing::TwoMassExperiment;
using driveid::testing::TwoMassTruth;

namespace {

JointParameters Joint(const TwoMassTruth& t) {
  JointParameters p;
  p.motor_inertia = t.motor_inertia;
  p.link_inertia = t.link_inertia;
  p.stiffness = t.stiffness;
  p.damping = t.damping;
  p.motor_viscous = t.motor_viscous;
  return p;
}

ResponseData ToData(const FrequencyResponse& r) {
  return {r.frequency, r.response, r.coherence, r.log_magnitude_std, r.phase_std, r.excitation, 0.0, 0.0};
}

FrequencyResponse Measure(const driveid::testing::TwoMassLog& log, double rate, bool with_reference,
                          double resolution = 0.0) {
  FrequencyRecord record{log.tau, log.qd_motor, with_reference ? log.r : std::vector<double>{}};
  FrequencyResponseOptions options;
  options.resolution = resolution;
  return EstimateFrequencyResponse({record}, rate, options);
}

}  // namespace

TEST_CASE("joint response: gradients match finite differences, resonances match the closed form") {
  const TwoMassTruth t;
  JointParameters p = Joint(t);
  p.link_viscous = 0.3;
  for (auto quantity : {ResponseQuantity::kPosition, ResponseQuantity::kRate, ResponseQuantity::kAcceleration}) {
    for (double omega : {3.0, 40.0, 75.0, 300.0}) {
      const JointResponse g = CalcJointResponse(p, t.gear_ratio, omega, quantity);
      double JointParameters::*members[] = {&JointParameters::motor_inertia, &JointParameters::link_inertia,
                                            &JointParameters::stiffness,     &JointParameters::damping,
                                            &JointParameters::motor_viscous, &JointParameters::link_viscous};
      for (int i = 0; i < 6; ++i) {
        JointParameters up = p, down = p;
        const double h = 1e-6 * p.*members[i];
        up.*members[i] += h;
        down.*members[i] -= h;
        const auto gu = CalcJointResponse(up, t.gear_ratio, omega, quantity);
        const auto gd = CalcJointResponse(down, t.gear_ratio, omega, quantity);
        const auto fd_motor = (std::log(gu.motor) - std::log(gd.motor)) / (2.0 * h);
        const auto fd_link = (std::log(gu.link) - std::log(gd.link)) / (2.0 * h);
        CHECK(std::abs(fd_motor - g.motor_log_gradient[i]) <= 1e-5 * std::abs(g.motor_log_gradient[i]) + 1e-8);
        CHECK(std::abs(fd_link - g.link_log_gradient[i]) <= 1e-5 * std::abs(g.link_log_gradient[i]) + 1e-8);
      }
    }
  }
  // Undamped: the motor response vanishes at the anti-resonance and is
  // unbounded at the resonance; the high-frequency asymptote is n^2 / J_m.
  JointParameters undamped = Joint(t);
  undamped.damping = undamped.motor_viscous = 0.0;
  const double wa = std::sqrt(t.stiffness / t.link_inertia);
  const double wr = std::sqrt(t.stiffness * (1.0 / t.motor_inertia + 1.0 / t.link_inertia));
  CHECK(JointAntiresonance(undamped) == wa);
  CHECK(JointResonance(undamped) == wr);
  CHECK(std::abs(CalcJointResponse(undamped, t.gear_ratio, wa, ResponseQuantity::kAcceleration).motor) < 1e-9);
  CHECK(std::abs(CalcJointResponse(undamped, t.gear_ratio, wr * (1 + 1e-9), ResponseQuantity::kAcceleration).motor) >
        1e6);
  const double high = std::abs(CalcJointResponse(undamped, t.gear_ratio, 1e5, ResponseQuantity::kAcceleration).motor);
  CHECK(std::abs(high - t.gear_ratio * t.gear_ratio / t.motor_inertia) < 1e-3 * high);
}

TEST_CASE("period detection finds a repeating excitation and nothing in noise") {
  TwoMassExperiment e;
  e.duration = 10.0;
  const auto log = SimulateTwoMassClosedLoop(TwoMassTruth{}, e);
  CHECK(DetectPeriod(log.r) == 2000);
  // The excitation under noise of 15 % of its rms still repeats (a logged
  // torque); at 40 % it does not count; white noise and a sweep never do.
  std::mt19937 random(3);
  std::normal_distribution<double> unit;
  double rms = 0.0;
  for (double v : log.r) rms += v * v;
  rms = std::sqrt(rms / static_cast<double>(log.r.size()));
  std::vector<double> noisy = log.r, noisier = log.r, noise(log.r.size()), sweep(log.r.size());
  for (std::size_t k = 0; k < noisy.size(); ++k) {
    const double g = unit(random);
    noisy[k] += 0.15 * rms * g;
    noisier[k] += 0.4 * rms * g;
    noise[k] = unit(random);
    const double t = static_cast<double>(k) / e.rate;
    sweep[k] = std::sin(2.0 * M_PI * (0.5 * t + 0.5 * t * t));
  }
  CHECK(DetectPeriod(noisy) == 2000);
  CHECK(DetectPeriod(noisier) == 0);
  CHECK(DetectPeriod(noise) == 0);
  CHECK(DetectPeriod(sweep) == 0);
}

TEST_CASE("closed loop, injected multisine: resonance, anti-resonance and the two-mass fit") {
  const TwoMassTruth truth;
  TwoMassExperiment e;
  const auto log = SimulateTwoMassClosedLoop(truth, e);
  const FrequencyResponse frf = Measure(log, e.rate, true);
  REQUIRE(frf.method == FrequencyMethod::kPeriodic);
  CHECK(frf.averages == 14);  // the first of 15 periods settles
  const double fa = JointAntiresonance(Joint(truth)) / (2 * M_PI), fr = JointResonance(Joint(truth)) / (2 * M_PI);
  TwoMassFitOptions options;
  options.hold_rate = e.rate;
  const ResponseFeatures read = ReadResponseFeatures(ToData(frf), ResponseQuantity::kRate, options.Band());
  CHECK(std::abs(read.resonance.value / fr - 1.0) < 0.02);
  CHECK(std::abs(read.antiresonance.value / fa - 1.0) < 0.02);

  JointSection start;
  start.gear_ratio = truth.gear_ratio;
  const TwoMassFitOutput fit = FitTwoMassResponse(ToData(frf), nullptr, start, options);
  const auto check = [&](const char* name, double value, double tolerance) {
    for (const auto& est : fit.fit.estimates) {
      if (est.name != name) continue;
      INFO(name << " = " << est.value << " +- " << est.standard_error << " truth " << value);
      CHECK(std::abs(est.value / value - 1.0) < tolerance);
      return;
    }
    FAIL(name << " not estimated");
  };
  check("motor_inertia", truth.motor_inertia, 0.05);
  check("link_inertia", truth.link_inertia, 0.05);
  check("stiffness", truth.stiffness, 0.05);
  check("damping", truth.damping, 0.25);
  CHECK(std::abs(fit.resonance.value / fr - 1.0) < 0.02);
  CHECK(std::abs(fit.antiresonance.value / fa - 1.0) < 0.02);
  CHECK(std::abs(fit.resonance.value - fr) < 3.0 * fit.resonance.standard_error);
  CHECK(std::abs(fit.antiresonance.value - fa) < 3.0 * fit.antiresonance.standard_error);
}

TEST_CASE("closed loop, noise excitation: the reference removes the feedback's bias that H1 has") {
  const TwoMassTruth truth;
  TwoMassExperiment e;
  e.excitation = Excitation::kNoise;
  e.amplitude = 1.0;
  e.disturbance = 0.3;
  e.duration = 60.0;
  const auto log = SimulateTwoMassClosedLoop(truth, e);
  const FrequencyResponse with_reference = Measure(log, e.rate, true, 0.25);
  REQUIRE(with_reference.method == FrequencyMethod::kWelch);
  REQUIRE(with_reference.closed_loop);
  TwoMassFitOptions options;
  options.hold_rate = e.rate;
  JointSection start;
  start.gear_ratio = truth.gear_ratio;
  const TwoMassFitOutput fit = FitTwoMassResponse(ToData(with_reference), nullptr, start, options);
  const double fa = JointAntiresonance(Joint(truth)) / (2 * M_PI), fr = JointResonance(Joint(truth)) / (2 * M_PI);
  INFO("resonance " << fit.resonance.value << " +- " << fit.resonance.standard_error << " truth " << fr);
  INFO("anti-resonance " << fit.antiresonance.value << " +- " << fit.antiresonance.standard_error << " truth " << fa);
  CHECK(std::abs(fit.resonance.value / fr - 1.0) < 0.02);
  CHECK(std::abs(fit.antiresonance.value / fa - 1.0) < 0.02);
  for (const auto& est : fit.fit.estimates) INFO(est.name << " " << est.value << " +- " << est.standard_error);
  INFO("band " << fit.band_low << " .. " << fit.band_high << " read " << fit.read.resonance.value << " "
               << fit.read.antiresonance.value);
  for (const auto& est : fit.fit.estimates) {
    if (est.name == "stiffness") CHECK(std::abs(est.value / truth.stiffness - 1.0) < 0.05);
  }
}

TEST_CASE("a response without its resonance in the band is refused") {
  const TwoMassTruth truth;
  TwoMassExperiment e;
  e.duration = 20.0;
  const auto log = SimulateTwoMassClosedLoop(truth, e);
  const FrequencyResponse frf = Measure(log, e.rate, true);
  TwoMassFitOptions options;
  options.band_low = 0.5;
  options.band_high = 8.0;  // below the resonance (11.6 Hz)
  JointSection start;
  start.gear_ratio = truth.gear_ratio;
  CHECK_THROWS_AS(FitTwoMassResponse(ToData(frf), nullptr, start, options), IdentificationError);
}

TEST_CASE("two-mass fit: 95 % intervals cover the truth over seeds (closed loop, AR(1) speed noise)") {
  const TwoMassTruth truth;
  const double values[] = {truth.motor_inertia, truth.link_inertia, truth.stiffness, truth.damping,
                           truth.motor_viscous};
  const int seeds = 20;
  int covered[5] = {0, 0, 0, 0, 0}, total = 0;
  for (int seed = 1; seed <= seeds; ++seed) {
    TwoMassExperiment e;
    e.seed = static_cast<std::uint64_t>(seed);
    const auto log = SimulateTwoMassClosedLoop(truth, e);
    TwoMassFitOptions options;
    options.hold_rate = e.rate;
    JointSection start;
    start.gear_ratio = truth.gear_ratio;
    const TwoMassFitOutput fit = FitTwoMassResponse(ToData(Measure(log, e.rate, true)), nullptr, start, options);
    REQUIRE(fit.fit.estimates.size() == 5);
    for (int j = 0; j < 5; ++j) {
      const auto& est = fit.fit.estimates[static_cast<std::size_t>(j)];
      const bool inside = est.ci95_low <= values[j] && values[j] <= est.ci95_high;
      covered[j] += inside;
      total += inside;
    }
  }
  // Measured: 93 of 100 (J_m 18, J_l 19, k 18, d 19, b_m 19 of 20).
  for (int j = 0; j < 5; ++j) {
    INFO("parameter " << j << " covered " << covered[j] << " of " << seeds);
    CHECK(covered[j] >= 16);
  }
  CHECK(total >= 88);
  CHECK(total <= 99);
}

TEST_CASE("periodic and Welch estimates are exact for a known system at any length, primes included") {
  // y[k] = 2 u[k-1]: H = 2 exp(-j w / rate) at every line; a random periodic
  // input whose period is the shortest read (4), smooth (1000), prime (1009)
  // or a large prime (100003).
  for (std::size_t period : {std::size_t{4}, std::size_t{1000}, std::size_t{1009}, std::size_t{100003}}) {
    std::mt19937_64 rng(period);
    std::normal_distribution<double> normal(0.0, 1.0);
    std::vector<double> one(period);
    for (auto& v : one) v = normal(rng);
    FrequencyRecord record;
    for (std::size_t i = 0; i < 5 * period; ++i) record.input.push_back(one[i % period]);
    record.output.push_back(2.0 * one[period - 1]);
    for (std::size_t i = 1; i < record.input.size(); ++i) record.output.push_back(2.0 * record.input[i - 1]);
    const double rate = 1000.0;
    const FrequencyResponse r = EstimateFrequencyResponse({record}, rate, {});
    REQUIRE(r.method == FrequencyMethod::kPeriodic);
    // Every line (a random line below 1e-3 of the largest counts as not excited).
    REQUIRE(static_cast<double>(r.frequency.size()) >= 0.999 * static_cast<double>(period / 2));
    double worst = 0.0;
    for (std::size_t b = 0; b < r.frequency.size(); ++b) {
      const std::complex<double> expected = 2.0 * std::exp(std::complex<double>(0.0, -2.0 * M_PI * r.frequency[b] / rate));
      worst = std::max(worst, std::abs(r.response[b] - expected));
    }
    INFO("period " << period);
    CHECK(worst < 1e-8);
  }
  // A given period shorter than 4 samples excites no line between DC and
  // Nyquist: refused by name (one sample used to crash the FFT).
  for (double samples : {1.0, 2.0, 3.0}) {
    FrequencyRecord record;
    for (int i = 0; i < 64; ++i) record.input.push_back(i % 2 == 0 ? 1.0 : -1.0);
    record.output = record.input;
    FrequencyResponseOptions options;
    options.period = samples / 1000.0;
    INFO("period of " << samples << " samples");
    CHECK_THROWS_WITH(EstimateFrequencyResponse({record}, 1000.0, options),
                      Catch::Contains("a period needs at least 4"));
  }
  // Welch with a prime segment length on white noise through the same system.
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  FrequencyRecord record;
  for (int i = 0; i < 40000; ++i) record.input.push_back(normal(rng));
  record.output.push_back(0.0);
  for (std::size_t i = 1; i < record.input.size(); ++i) record.output.push_back(2.0 * record.input[i - 1]);
  FrequencyResponseOptions options;
  options.method = FrequencyMethod::kWelch;
  options.resolution = 1000.0 / 4001.0;  // 4001 samples, prime
  const FrequencyResponse w = EstimateFrequencyResponse({record}, 1000.0, options);
  REQUIRE(w.resolution == 1000.0 / 4001.0);
  double worst = 0.0;
  for (std::size_t b = 0; b < w.frequency.size(); b += 97) {
    const std::complex<double> expected = 2.0 * std::exp(std::complex<double>(0.0, -2.0 * M_PI * w.frequency[b] / 1000.0));
    worst = std::max(worst, std::abs(w.response[b] - expected) / 2.0);
  }
  CHECK(worst < 0.05);  // the one-sample delay against the Hann window's length
}

TEST_CASE("a read resonance's std holds by Monte Carlo (closed loop; noise and multisine excitation)") {
  // The read frequencies against the truth's undamped resonance and
  // anti-resonance over seeds: |z| < 1.96 in about 95 % of the runs, from
  // both sides (neither too narrow nor far too wide).
  const TwoMassTruth truth;
  const double fa = JointAntiresonance(Joint(truth)) / (2 * M_PI), fr = JointResonance(Joint(truth)) / (2 * M_PI);
  for (Excitation excitation : {Excitation::kNoise, Excitation::kMultisine}) {
    int inside_r = 0, inside_a = 0, narrow = 0, runs = 0;
    double sum_z2 = 0.0;
    for (int seed = 1; seed <= 40; ++seed) {
      TwoMassExperiment e;
      e.excitation = excitation;
      e.amplitude = excitation == Excitation::kNoise ? 1.0 : 0.3;
      e.duration = 30.0;
      e.seed = static_cast<std::uint64_t>(seed);
      const auto log = SimulateTwoMassClosedLoop(truth, e);
      const FrequencyResponse frf = Measure(log, e.rate, true, excitation == Excitation::kNoise ? 0.5 : 0.0);
      ResponseData data = ToData(frf);
      data.nyquist_hz = 0.5 * e.rate;
      const ResponseFeatures read = ReadResponseFeatures(data, ResponseQuantity::kRate, ResponseBand{});
      REQUIRE(read.resonance.value > 0.0);
      REQUIRE(read.antiresonance.value > 0.0);
      const double zr = (read.resonance.value - fr) / read.resonance.standard_error;
      const double za = (read.antiresonance.value - fa) / read.antiresonance.standard_error;
      UNSCOPED_INFO("seed " << seed << " resonance " << read.resonance.value << " +- " << read.resonance.standard_error
                            << " (z " << zr << "), anti-resonance " << read.antiresonance.value << " +- "
                            << read.antiresonance.standard_error << " (z " << za << ")");
      inside_r += std::abs(zr) < 1.96;
      inside_a += std::abs(za) < 1.96;
      narrow += std::abs(zr) < 0.5;
      sum_z2 += zr * zr + za * za;
      ++runs;
    }
    INFO("resonance covered " << inside_r << ", anti-resonance " << inside_a << " of " << runs << "; mean z^2 "
                              << sum_z2 / (2 * runs));
    CHECK(inside_r >= 34);
    CHECK(inside_a >= 34);
    CHECK(sum_z2 / (2 * runs) > 0.3);  // not far too wide
    CHECK(sum_z2 / (2 * runs) < 2.0);
  }
}

TEST_CASE("a disturbance line in the input and a peak beyond the excited band are not read as the resonance") {
  const TwoMassTruth truth;
  TwoMassExperiment e;
  e.excitation = Excitation::kNoise;
  e.amplitude = 1.0;
  e.duration = 30.0;
  auto log = SimulateTwoMassClosedLoop(truth, e);
  // A disturbance at 30 Hz that the loop passes to the torque: a line in the
  // input's own spectrum, with an output far larger than the plant gives.
  const double fd = 30.0;
  for (std::size_t i = 0; i < log.t.size(); ++i) {
    log.tau[i] += 3.0 * std::sin(2 * M_PI * fd * log.t[i]);
    log.qd_motor[i] += 40.0 * std::sin(2 * M_PI * fd * log.t[i] + 0.3);
  }
  FrequencyRecord record{log.tau, log.qd_motor, {}};
  FrequencyResponseOptions options;
  options.resolution = 0.5;
  const FrequencyResponse frf = EstimateFrequencyResponse({record}, e.rate, options);
  ResponseData data = ToData(frf);
  data.nyquist_hz = 0.5 * e.rate;
  const ResponseFeatures read = ReadResponseFeatures(data, ResponseQuantity::kRate, ResponseBand{});
  const double fr = JointResonance(Joint(truth)) / (2 * M_PI);
  INFO("resonance " << read.resonance.value << " +- " << read.resonance.standard_error);
  CHECK(std::abs(read.resonance.value / fr - 1.0) < 0.05);
  REQUIRE(!read.notes.empty());
  CHECK(read.notes.front().find("line of the excitation") != std::string::npos);

  // The same response with its excitation only up to 8 Hz (below the
  // resonance): nothing is read above the excited band.
  ResponseData low = ToData(frf);
  for (std::size_t b = 0; b < low.frequency.size(); ++b) {
    if (low.frequency[b] > 8.0) low.excitation[b] = 0.0;
  }
  const ResponseFeatures below = ReadResponseFeatures(low, ResponseQuantity::kRate, ResponseBand{});
  CHECK(below.band_high <= 8.0);
  CHECK(below.resonance.value < 8.0);
  // Excited up to 3 Hz only: too few bins inside the band for a peak, said.
  for (std::size_t b = 0; b < low.frequency.size(); ++b) {
    if (low.frequency[b] > 3.0) low.excitation[b] = 0.0;
  }
  const ResponseFeatures none = ReadResponseFeatures(low, ResponseQuantity::kRate, ResponseBand{});
  CHECK(none.resonance.value == 0.0);
  REQUIRE(!none.warnings.empty());
  CHECK(none.warnings.front().find("no resonance") != std::string::npos);
}

TEST_CASE("a measured phase that lags linearly: the two-mass fit says to free the delay, and then fits it") {
  const TwoMassTruth truth;
  TwoMassExperiment e;
  const auto log = SimulateTwoMassClosedLoop(truth, e);
  FrequencyResponse frf = Measure(log, e.rate, true);
  TwoMassFitOptions options;
  options.hold_rate = e.rate;
  JointSection start;
  start.gear_ratio = truth.gear_ratio;
  const auto phase_warned = [](const TwoMassFitOutput& fit) {
    for (const auto& w : fit.fit.warnings) {
      if (w.find("phase: the measured phase falls away from the model linearly") == 0) return true;
    }
    return false;
  };
  CHECK_FALSE(phase_warned(FitTwoMassResponse(ToData(frf), nullptr, start, options)));
  // A 2 ms lag (a bus, a filter) on the measured response.
  constexpr double kLag = 0.002;
  for (std::size_t b = 0; b < frf.frequency.size(); ++b) {
    frf.response[b] *= std::exp(std::complex<double>(0.0, -2.0 * M_PI * frf.frequency[b] * kLag));
  }
  // Warned, or refused (the lag leaves damping undetermined) with the warning.
  try {
    const TwoMassFitOutput lagged = FitTwoMassResponse(ToData(frf), nullptr, start, options);
    CHECK(phase_warned(lagged));
  } catch (const IdentificationError& refused) {
    CHECK_THAT(refused.what(), Catch::Contains("phase: the measured phase falls away from the model linearly"));
  }
  options.free.push_back("delay");
  const TwoMassFitOutput with_delay = FitTwoMassResponse(ToData(frf), nullptr, start, options);
  CHECK_FALSE(phase_warned(with_delay));
  INFO("delay " << with_delay.delay);
  CHECK(std::abs(with_delay.delay - kLag) < 1e-4);
}

TEST_CASE("a drive's Bode export behind any delay of 0 to 10 ms: the delay and the joint are fitted") {
  // The two-mass rate response written here from the equations of motion
  // (link side, torque n tau on the motor), times e^(-s tau), on 400
  // log-spaced bins over 1 .. 400 Hz, with 2 % magnitude and 1 degree
  // phase noise, as a drive's export gives it (no std per bin).
  const double n = 10.0, jm = 0.5, jl = 1.5, k = 2000.0, d = 2.0, bm = 6.0;
  std::mt19937 random(7);
  std::normal_distribution<double> unit;
  for (double delay : {0.0, 0.0015, 0.003, 0.006, 0.010}) {
    ResponseData data;
    for (int i = 0; i < 400; ++i) {
      const double f = std::pow(400.0, i / 399.0);
      const std::complex<double> s(0.0, 2.0 * M_PI * f);
      const std::complex<double> al = jl * s * s + d * s + k, am = jm * s * s + (d + bm) * s + k;
      const std::complex<double> h = n * n * s * al / (am * al - (d * s + k) * (d * s + k)) * std::exp(-s * delay);
      data.frequency.push_back(f);
      data.response.push_back(h * std::exp(0.02 * unit(random)) *
                              std::exp(std::complex<double>(0.0, M_PI / 180.0 * unit(random))));
    }
    TwoMassFitOptions options;
    options.free = {"motor_inertia", "link_inertia", "stiffness", "damping", "motor_viscous", "delay"};
    JointSection start;
    start.gear_ratio = n;
    INFO("delay " << delay);
    const TwoMassFitOutput fit = FitTwoMassResponse(data, nullptr, start, options);
    const auto estimate = [&](const std::string& name) {
      for (const auto& e : fit.fit.estimates) {
        if (e.name == name) return e;
      }
      FAIL("no estimate " << name);
      return fit.fit.estimates.front();
    };
    const auto tau = estimate("delay"), stiffness = estimate("stiffness"), damping = estimate("damping");
    INFO("fitted " << tau.value << " +- " << tau.standard_error << ", k " << stiffness.value << " +- "
                   << stiffness.standard_error << ", d " << damping.value << " +- " << damping.standard_error);
    CHECK(std::abs(tau.value - delay) < 4.0 * tau.standard_error + 1e-7);
    CHECK(std::abs(stiffness.value - k) < 4.0 * stiffness.standard_error);
    CHECK(std::abs(damping.value - d) < 4.0 * damping.standard_error);
  }
}
