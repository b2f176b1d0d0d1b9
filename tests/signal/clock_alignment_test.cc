// Clock alignment (signal/clock_alignment.h) on two records of one motion
// as separate loggers write them: different rates, jittered stamps,
// quantised encoders, noise, an unknown offset and a clock-rate error.
// The motion is generated here from random sinusoids and steps, independently
// of the code under test.
#include "signal/clock_alignment.h"

#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include "core/errors.h"

using namespace driveid;

namespace {

struct Motion {
  std::vector<double> f, a, p;  // sinusoids
  double operator()(double t) const {
    double v = 0.0;
    for (std::size_t k = 0; k < f.size(); ++k) v += a[k] * std::sin(2.0 * M_PI * f[k] * t + p[k]);
    // Moves of 50 ms (a motion is continuous): not periodic.
    return v + 0.25 * (1.0 + std::tanh((t - 3.0) / 0.05)) - 0.4 * (1.0 + std::tanh((t - 7.5) / 0.05));
  }
};

Motion RandomMotion(std::mt19937& rng) {
  std::uniform_real_distribution<double> freq(0.1, 4.0), amp(0.2, 1.0), phase(0.0, 2.0 * M_PI);
  Motion m;
  for (int k = 0; k < 6; ++k) {
    m.f.push_back(freq(rng));
    m.a.push_back(amp(rng));
    m.p.push_back(phase(rng));
  }
  return m;
}

// A logger on its own clock: it samples at nominal instants t (with
// jitter), stamping clock_start + (t - begin)(1 + ppm 1e-6).
struct Record {
  std::vector<double> t, x;
};

Record Log(const Motion& m, std::mt19937& rng, double begin, double end, double hz, double clock_start,
           double clock_ppm, double noise, double quantum) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> jitter(-0.05 / hz, 0.05 / hz);
  Record r;
  for (double t = begin; t < end; t += 1.0 / hz) {
    r.t.push_back(clock_start + (t - begin) * (1.0 + 1e-6 * clock_ppm));
    const double v = m(t + jitter(rng)) + noise * gauss(rng);
    r.x.push_back(quantum > 0.0 ? quantum * std::round(v / quantum) : v);
  }
  return r;
}

}  // namespace

TEST_CASE("a shift between two clocks found within a tenth of a step, over 20 random motions") {
  std::mt19937 rng(7);
  for (int seed = 0; seed < 20; ++seed) {
    const Motion m = RandomMotion(rng);
    // a: 1 kHz from t = 0 on a clock starting at 0; b: 500 Hz from t = 1.3 s on a clock starting at 1e5 s.
    const Record a = Log(m, rng, 0.0, 10.0, 1000.0, 0.0, 0.0, 0.01, 1e-3);
    const Record b = Log(m, rng, 1.3003, 9.0, 500.0, 1e5, 0.0, 0.02, 0.0);
    // b's stamp 1e5 is true time 1.3003 = a's time 1.3003: a-time = b-time + (1.3003 - 1e5).
    const ChannelShift s = ShiftByCrossCorrelation(a.t, a.x, b.t, b.x);
    INFO("seed " << seed);
    CHECK(std::abs(s.shift - (1.3003 - 1e5)) < 0.2e-3);  // a tenth of the 2 ms grid
    CHECK(s.correlation > 0.95);
    const ClockMap map = AlignClocks(a.t, a.x, b.t, b.x, "test");
    INFO(map.notes.back());
    CHECK(std::abs(map.scale * 1e5 + map.offset - 1.3003) < 2e-4);
  }
}

TEST_CASE("a clock running 200 ppm fast is found and corrected: the ends align within half a millisecond") {
  std::mt19937 rng(11);
  const Motion m = RandomMotion(rng);
  const Record a = Log(m, rng, 0.0, 60.0, 1000.0, 0.0, 0.0, 0.01, 1e-3);
  const Record b = Log(m, rng, 0.5, 59.0, 1000.0, 20.0, 200.0, 0.01, 1e-3);
  const ClockMap map = AlignClocks(a.t, a.x, b.t, b.x, "test");
  CHECK(map.notes.size() == 2);
  // True time t is b-stamp 20 + (t - 0.5)(1 + 2e-4); a-time = t.
  for (double t : {1.0, 30.0, 58.0}) {
    const double stamp = 20.0 + (t - 0.5) * (1.0 + 2e-4);
    CHECK(std::abs(map.scale * stamp + map.offset - t) < 0.5e-3);
  }
  CHECK(map.scale == Approx(1.0 / (1.0 + 2e-4)).epsilon(2e-5));
  // Without drift no correction is made.
  const Record c = Log(m, rng, 0.5, 59.0, 1000.0, 20.0, 0.0, 0.01, 1e-3);
  const ClockMap plain = AlignClocks(a.t, a.x, c.t, c.x, "test");
  CHECK(plain.scale == 1.0);
  CHECK(plain.notes.size() == 1);
}

TEST_CASE("a winding motor angle (its level drifts) through an encoder: aligned within a fifth of a millisecond") {
  std::mt19937 rng(5);
  const Motion m = RandomMotion(rng);
  Record a = Log(m, rng, 0.0, 20.0, 1000.0, 0.0, 0.0, 0.0, 0.0);
  Record b = Log(m, rng, 2.0, 18.0, 500.0, 50.0, 0.0, 0.0, 0.0);
  // Angle 12 t + motion, through a 4096-count encoder.
  const auto wind = [](Record& r, double t0) {
    for (std::size_t k = 0; k < r.t.size(); ++k) {
      const double t = t0 + (r.t[k] - r.t.front());
      r.x[k] = std::round((12.0 * t + r.x[k]) * 4096.0 / (2.0 * M_PI)) * 2.0 * M_PI / 4096.0;
    }
  };
  wind(a, 0.0);
  wind(b, 2.0);
  const ClockMap map = AlignClocks(a.t, a.x, b.t, b.x, "angle");
  CHECK(std::abs(map.offset - (2.0 - 50.0)) < 0.2e-3);
}

TEST_CASE("refused: unrelated channels, and a periodic channel whose shift is ambiguous") {
  std::mt19937 rng(3);
  std::vector<double> ta, xa, tb, xb;
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (int k = 0; k < 4000; ++k) {
    ta.push_back(0.001 * k);
    xa.push_back(gauss(rng));
    tb.push_back(0.001 * k);
    xb.push_back(gauss(rng));
  }
  CHECK_THROWS_AS(AlignClocks(ta, xa, tb, xb, "white"), IdentificationError);
  try {
    AlignClocks(ta, xa, tb, xb, "white noise");
  } catch (const IdentificationError& e) {
    CHECK_THAT(e.what(), Catch::Contains("white noise: the channels do not line up"));
  }
  // A pure 2 Hz sine over 10 s: shifts 0.5 s apart correlate alike.
  for (std::size_t k = 0; k < ta.size(); ++k) {
    xa[k] = std::sin(2.0 * M_PI * 2.0 * ta[k] * 2.5);
    xb[k] = std::sin(2.0 * M_PI * 2.0 * (tb[k] - 0.1) * 2.5);
  }
  CHECK_THROWS_WITH(AlignClocks(ta, xa, tb, xb, "sine"), Catch::Contains("sine: the alignment is ambiguous"));
}

TEST_CASE("refused: stamps with a gap that would make the common grid huge") {
  std::vector<double> t, x;
  for (int k = 0; k < 100; ++k) {
    t.push_back(k < 50 ? 0.001 * k : 1e9 + 0.001 * k);
    x.push_back(std::sin(0.1 * k * k));
  }
  CHECK_THROWS_WITH(AlignClocks(t, x, t, x, "gap"), Catch::Contains("gap: a record spans 1e+09 s"));
}
