// Elastic joint (docs/models.md#elastic-joint): recovery of a two-mass joint
// from the test's own generator (RK4, smooth Coulomb), intervals that cover
// the truth over seeds under correlated torque noise, refusals by name.
#include "fit/joint/joint_fit.h"

#include <cmath>
#include <random>
#include <string>

#include <catch2/catch.hpp>

#include "core/errors.h"

using namespace driveid;

namespace {

struct Truth {
  double n = 50, jm = 0.02, jl = 0.05, k = 20.0, d = 0.05, bm = 0.1, cm = 0.2, bl = 0.05, cl = 0.1, offset = 0.05;
};

// Motor-shaft torque: a multisine over the resonance (5.9 Hz); state
// (theta_m, w_m, theta_l, w_l) by RK4 with 1e-4 s steps; Coulomb as
// c tanh(w / 1e-3). Logged at 1 kHz: q_motor = n theta_m quantised to
// 2 pi / 4096, q_link to 2 pi / 2^20, tau with AR(1) noise (phi, sd).
JointLog MakeLog(const Truth& p, unsigned seed, double phi, double sd, bool link_moves = true, int samples = 20000) {
  std::mt19937 random(seed);
  std::normal_distribution<double> z(0.0, 1.0);
  const auto drive = [&](double t) {
    return (2.0 * std::sin(2 * M_PI * 0.4 * t) + 0.8 * std::sin(2 * M_PI * 2.3 * t + 1.0) +
            0.4 * std::sin(2 * M_PI * 5.5 * t + 2.0) + 0.3 * std::sin(2 * M_PI * 8.1 * t + 0.5)) /
           p.n;
  };
  const auto field = [&](double t, const double* x, double* dx) {
    const double tm = p.n * drive(t), spring = p.k * (x[0] - x[2]) + p.d * (x[1] - x[3]);
    dx[0] = x[1];
    dx[1] = (tm - spring - p.bm * x[1] - p.cm * std::tanh(x[1] / 1e-3) - p.offset) / p.jm;
    dx[2] = x[3];
    dx[3] = link_moves ? (spring - p.bl * x[3] - p.cl * std::tanh(x[3] / 1e-3)) / p.jl : 0.0;
  };
  JointLog log;
  log.path = "joint.csv";
  double x[4] = {0, 0, 0, 0}, t = 0.0, noise = 0.0;
  const double h = 1e-4, qm = 2 * M_PI / 4096, ql = 2 * M_PI / (1 << 20);
  for (int s = 0; s <= samples; ++s) {
    noise = phi * noise + sd * std::sqrt(1 - phi * phi) * z(random);
    log.time.push_back(s * 1e-3);
    log.motor_position.push_back(qm * std::round(p.n * x[0] / qm));
    log.link_position.push_back(ql * std::round(x[2] / ql));
    log.torque.push_back(drive(t) + noise);
    for (int m = 0; m < 10; ++m) {
      double k1[4], k2[4], k3[4], k4[4], y[4];
      field(t, x, k1);
      for (int i = 0; i < 4; ++i) y[i] = x[i] + 0.5 * h * k1[i];
      field(t + 0.5 * h, y, k2);
      for (int i = 0; i < 4; ++i) y[i] = x[i] + 0.5 * h * k2[i];
      field(t + 0.5 * h, y, k3);
      for (int i = 0; i < 4; ++i) y[i] = x[i] + h * k3[i];
      field(t + h, y, k4);
      for (int i = 0; i < 4; ++i) x[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
      t += h;
    }
  }
  return log;
}

JointSection Start() {
  JointSection s;
  s.gear_ratio = 50;
  return s;
}

double Estimate(const FitResult& fit, const std::string& name, double* low = nullptr, double* high = nullptr) {
  for (const auto& e : fit.estimates) {
    if (e.name == name) {
      if (low) *low = e.ci95_low;
      if (high) *high = e.ci95_high;
      return e.value;
    }
  }
  FAIL("no estimate " << name);
  return 0.0;
}

}  // namespace

TEST_CASE("joint: two masses recovered, k within 2 %, d within 10 %") {
  const Truth truth;
  const JointFitOutput out = FitJoint({MakeLog(truth, 1, 0.0, 0.0005)}, Start(), {});
  CHECK(Estimate(out.fit, "stiffness") == Approx(truth.k).epsilon(0.02));
  CHECK(Estimate(out.fit, "damping") == Approx(truth.d).epsilon(0.10));
  CHECK(Estimate(out.fit, "motor_inertia") == Approx(truth.jm).epsilon(0.03));
  CHECK(Estimate(out.fit, "link_inertia") == Approx(truth.jl).epsilon(0.03));
  CHECK(Estimate(out.fit, "motor_viscous") == Approx(truth.bm).epsilon(0.05));
  CHECK(Estimate(out.fit, "motor_coulomb") == Approx(truth.cm).epsilon(0.05));
  CHECK(out.params.stiffness == Estimate(out.fit, "stiffness"));
}

TEST_CASE("joint: the intervals of k and d cover the truth under AR(1) torque noise") {
  const Truth truth;
  int covered_k = 0, covered_d = 0, runs = 0;
  double sum = 0, sum2 = 0, reported = 0;  // of k: the spread over seeds against the reported std
  for (unsigned seed = 10; seed < 30; ++seed) {
    JointFitOptions coverage;
    coverage.sensitivity = false;  // the intervals only; the refits at other cutoffs are checked elsewhere
    const JointFitOutput out = FitJoint({MakeLog(truth, seed, 0.9, 0.003, true, 10000)}, Start(), coverage);
    double lo = 0, hi = 0;
    const double k = Estimate(out.fit, "stiffness", &lo, &hi);
    sum += k;
    sum2 += k * k;
    reported += (hi - lo) / (2 * 1.96);
    covered_k += truth.k >= lo && truth.k <= hi;
    Estimate(out.fit, "damping", &lo, &hi);
    covered_d += truth.d >= lo && truth.d <= hi;
    ++runs;
  }
  const double spread = std::sqrt(sum2 / runs - (sum / runs) * (sum / runs)), mean_std = reported / runs;
  INFO("coverage k " << covered_k << ", d " << covered_d << " of " << runs << "; k spread " << spread
                     << " vs reported std " << mean_std);
  CHECK(mean_std > 0.6 * spread);  // not too narrow
  CHECK(mean_std < 2.0 * spread);  // nor too wide
  CHECK(covered_k >= 16);  // 95 % nominal: 19 expected of 20, P(<= 15) < 0.2 %
  CHECK(covered_d >= 16);
}

TEST_CASE("joint: a link that never moves leaves the link terms undetermined; refusals name them") {
  const Truth truth;
  try {
    FitJoint({MakeLog(truth, 2, 0.0, 0.0005, false)}, Start(), {});
    FAIL("no refusal");
  } catch (const IdentificationError& e) {
    const std::string message = e.what();
    CHECK(message.find("link_inertia") != std::string::npos);
  }
  CHECK_THROWS_AS(FitJoint({MakeLog(truth, 3, 0.0, 0.0005)}, JointSection{}, {}), InputError);  // no gear ratio
  JointFitOptions bad;
  bad.free = {"stiffness", "mass"};
  CHECK_THROWS_AS(FitJoint({MakeLog(truth, 3, 0.0, 0.0005)}, Start(), bad), OptionError);
}

TEST_CASE("joint: isolated time-stamp glitches are resampled with a note; larger ones are refused") {
  const Truth truth;
  JointLog log = MakeLog(truth, 1, 0.0, 0.0005);
  // Five stamps 2.3 % of a step early (as a logger's clock glitch writes them).
  for (std::size_t k : {3000u, 7000u, 11000u, 15000u, 18000u}) log.time[k] -= 0.023e-3;
  const JointFitOutput out = FitJoint({log}, Start(), {});
  REQUIRE(!out.fit.notes.empty());
  CHECK(out.fit.notes.front().find("isolated time-stamp glitches") != std::string::npos);
  CHECK(Estimate(out.fit, "stiffness") == Approx(truth.k).epsilon(0.02));
  CHECK(Estimate(out.fit, "motor_inertia") == Approx(truth.jm).epsilon(0.03));
  // One interval 10 % off is no glitch: the refusal names the log.
  log.time[3000] -= 0.1e-3;
  CHECK_THROWS_WITH(FitJoint({log}, Start(), {}), Catch::Contains("joint.csv: time steps"));
}
