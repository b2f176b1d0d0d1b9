// Monte-Carlo calibration of the reported standard errors (ctest label
// `slow`): over many independent noise realisations from the independent
// reference generators, the empirical standard deviation of each estimate
// must match the mean reported standard error from both sides (ratio within
// 0.85-1.15) and the 95 % intervals must cover the truth about 95 % of the
// time. With 400 seeds the ratio itself scatters by about 3.5 % (1 / sqrt(2 N)),
// so the band is over four of its standard deviations wide on each side.
#include <array>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "fit/axis/axis_fit.h"
#include "fit/axis/axis_oe_fit.h"
#include "fit/joint/joint_fit.h"
#include "fit/joint/joint_oe_fit.h"
#include "fit/step/step_fit.h"
#include "support/paper000.h"
#include "support/reference_drivetrain.h"
#include "support/friction_joint_cases.h"

using namespace driveid;

namespace {

// Estimates of one parameter over the seeds.
struct Sample {
  std::vector<double> value, reported_std;
  int covered = 0;

  void Add(const ParameterEstimate& e, double truth) {
    value.push_back(e.value);
    reported_std.push_back(e.standard_error);
    covered += e.ci95_low <= truth && truth <= e.ci95_high;
  }
  double Ratio() const {  // empirical std / mean reported std
    const double n = static_cast<double>(value.size());
    double mean = 0.0, reported = 0.0;
    for (double v : value) mean += v / n;
    double variance = 0.0;
    for (double v : value) variance += (v - mean) * (v - mean) / (n - 1.0);
    for (double s : reported_std) reported += s / n;
    return std::sqrt(variance) / reported;
  }
  double Coverage() const { return static_cast<double>(covered) / static_cast<double>(value.size()); }
};

const ParameterEstimate& Find(const FitResult& fit, const std::string& name) {
  for (const auto& e : fit.estimates) {
    if (e.name == name) return e;
  }
  throw std::logic_error("no estimate " + name);
}

void CheckCalibrated(const std::string& name, const Sample& sample) {
  INFO(name << ": empirical / reported std = " << sample.Ratio() << ", 95 % coverage " << sample.Coverage());
  CHECK(sample.Ratio() > 0.85);
  CHECK(sample.Ratio() < 1.15);
  CHECK(sample.Coverage() >= 0.91);
  CHECK(sample.Coverage() <= 0.99);
}

}  // namespace

namespace {

// The step fit (reduced model, start 2-3x off) over seeds [first, first +
// count) of the reference generator with strain-gauge noise sigma 0.1 N m,
// AR(1) with lag-1 `rho`: d_g, Theta_motor, tau_c.
struct StepSamples {
  Sample viscous, inertia, coulomb;
};

StepSamples FitStepSeeds(unsigned first, unsigned count, double rho) {
  const reference::DriveTrain truth;
  const double true_inertia = truth.J / (truth.n_g * truth.n_g);
  DriveTrainParameters start = testing_support::PaperDriveTrain();
  start.motor_inertia = true_inertia * 2.5;
  start.viscous_friction = truth.d_g / 3.0;
  start.coulomb_friction = truth.tau_c * 2.0;
  StepSamples out;
  for (unsigned seed = first; seed < first + count; ++seed) {
    const auto log = reference::SimulateStep(truth, 1000.0, 0.2, 0.02, -0.8, 0.1, 0.0, seed, rho);
    const auto fit = FitStepResponses({{"mc.csv", log.t, log.tau_motor, log.tau_link, {}, {}}}, start, {});
    out.viscous.Add(Find(fit.fit, "d_g"), truth.d_g);
    out.inertia.Add(Find(fit.fit, "Theta_motor"), true_inertia);
    out.coulomb.Add(Find(fit.fit, "tau_c"), truth.tau_c);
  }
  return out;
}

}  // namespace

TEST_CASE("step fit, reduced model, white strain-gauge noise: reported std calibrated over 400 seeds") {
  const StepSamples s = FitStepSeeds(1000, 400, 0.0);
  CheckCalibrated("d_g", s.viscous);
  CheckCalibrated("Theta_motor", s.inertia);
  CheckCalibrated("tau_c", s.coulomb);
}

TEST_CASE("step fit, reduced model, AR(1) 0.9 strain-gauge noise: intervals cover over 200 seeds") {
  const StepSamples samples = FitStepSeeds(3000, 200, 0.9);
  for (const auto& [name, s] : {std::pair<const char*, const Sample*>{"d_g", &samples.viscous},
                                {"Theta_motor", &samples.inertia}, {"tau_c", &samples.coulomb}}) {
    INFO("step, AR(1) 0.9, " << name << ": empirical / reported std = " << s->Ratio() << ", 95 % coverage "
                             << s->Coverage());
    CHECK(s->Coverage() >= 0.90);
    CHECK(s->Coverage() <= 0.98);
  }
}

namespace {

// An axis log from its own generator (not lib/sim): a two-sine position
// q = 0.8 sin(2 pi 0.4 t) + 0.3 sin(2 pi 1.3 t + 0.5) [rad] read by a 13-bit
// encoder (2 pi / 8192 quanta), and tau = J q'' + b q' + tau_c sgn(q') + tau_0
// + AR(1) noise e_k = rho e_{k-1} + sqrt(1 - rho^2) sigma w_k (stationary std
// sigma), 1 kHz for 20 s. quantum: the encoder's step (2 pi / 8192 for 13 bits).
AxisLog MakeAxisLog(double rho, double sigma, double quantum, unsigned seed) {
  const double J = 0.05, b = 0.2, tau_c = 0.3, tau_0 = 0.1;
  std::mt19937_64 random(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  AxisLog log;
  log.path = "mc.csv";
  double e = sigma * normal(random);
  for (int k = 0; k <= 20000; ++k) {
    const double t = k / 1000.0;
    const double w1 = 2.0 * M_PI * 0.4, w2 = 2.0 * M_PI * 1.3;
    const double q = 0.8 * std::sin(w1 * t) + 0.3 * std::sin(w2 * t + 0.5);
    const double qd = 0.8 * w1 * std::cos(w1 * t) + 0.3 * w2 * std::cos(w2 * t + 0.5);
    const double qdd = -0.8 * w1 * w1 * std::sin(w1 * t) - 0.3 * w2 * w2 * std::sin(w2 * t + 0.5);
    if (k > 0) e = rho * e + std::sqrt(1.0 - rho * rho) * sigma * normal(random);
    log.time.push_back(t);
    log.position.push_back(std::round(q / quantum) * quantum);
    log.force.push_back(J * qdd + b * qd + tau_c * ((qd > 0) - (qd < 0)) + tau_0 + e);
  }
  return log;
}

// Coverage of the four axis terms over `seeds` fits (`fit(seed)`), each
// within [low, high]; `label` names the case in messages.
void CheckAxisCoverage(const std::string& label, int seeds, const std::function<FitResult(unsigned)>& fit,
                       const std::array<double, 4>& truth, double low, double high) {
  Sample inertia, viscous, coulomb, offset;
  for (int seed = 0; seed < seeds; ++seed) {
    const FitResult result = fit(static_cast<unsigned>(seed));
    inertia.Add(Find(result, "inertia"), truth[0]);
    viscous.Add(Find(result, "viscous"), truth[1]);
    coulomb.Add(Find(result, "coulomb"), truth[2]);
    offset.Add(Find(result, "offset"), truth[3]);
  }
  for (const auto& [name, s] : {std::pair<const char*, const Sample*>{"inertia", &inertia}, {"viscous", &viscous},
                                {"coulomb", &coulomb}, {"offset", &offset}}) {
    INFO(label << ", " << name << ": empirical / reported std = " << s->Ratio() << ", 95 % coverage "
               << s->Coverage());
    CHECK(s->Coverage() >= low);
    CHECK(s->Coverage() <= high);
  }
}

void AxisCoverage(double rho, double quantum, int seeds, double low, double high) {
  CheckAxisCoverage(
      "rho " + std::to_string(rho), seeds,
      [&](unsigned seed) { return FitAxis({MakeAxisLog(rho, 0.05, quantum, 7000u + seed)}, AxisSection{}, {}).fit; },
      {0.05, 0.2, 0.3, 0.1}, low, high);
}

}  // namespace

// White noise: 400 seeds, so that the coverage's own scatter (binomial,
// 1.1 %) leaves the band [0.92, 0.97] 2.7 and 1.8 of its std from 95 %.
// (200 seeds and 0.93 were 1.3 std: leaving out 30 ms around reversals
// instead of 20 took viscous from 188 to 185 of 200 seeds, std ratio 1.03
// both, and 374 of 400 to 369, ratio 1.044 -> 1.049.)
TEST_CASE("axis fit, white and AR(1) 0.9 torque noise, fine encoder: intervals cover over 400 and 200 seeds") {
  AxisCoverage(0.0, 1e-9, 400, 0.92, 0.97);
  AxisCoverage(0.9, 1e-9, 200, 0.90, 0.98);
}

TEST_CASE("axis fit, 13-bit encoder, AR(1) 0.9 and 0.99 noise: intervals cover") {
  const double quantum = 2.0 * M_PI / 8192.0;
  AxisCoverage(0.9, quantum, 200, 0.90, 0.98);
  AxisCoverage(0.99, quantum, 200, 0.90, 0.98);
}

namespace {

// Output error's own generator (not lib/sim): an axis J 0.05, b 0.2,
// tau_c 1, tau_0 0.3 under held torque steps (0, 2, -2, 0.6, -1.6, 1.9 N m,
// 0.6 s each, 1 kHz), explicit Euler with 1e-6 s steps, sticking at rest
// while |u - tau_0| <= tau_c. Logged: q with white noise 2e-4 rad, then a
// 13-bit encoder's quantisation; the rate with AR(1) noise (rho, std 0.05).
AxisLog MakeStepAxisLog(double rho, unsigned seed) {
  const double J = 0.05, b = 0.2, c = 1.0, o = 0.3, quantum = 2.0 * M_PI / 8192.0;
  const double torque[] = {0.0, 2.0, -2.0, 0.6, -1.6, 1.9};
  std::mt19937_64 random(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  AxisLog log;
  log.path = "oe_mc.csv";
  double q = 0.0, v = 0.0, e = 0.05 * normal(random);
  for (int k = 0; k < 3600; ++k) {
    const double u = torque[k / 600];
    e = rho * e + std::sqrt(1.0 - rho * rho) * 0.05 * normal(random);
    log.time.push_back(k / 1000.0);
    log.position.push_back(std::round((q + 2e-4 * normal(random)) / quantum) * quantum);
    log.rate.push_back(v + e);
    log.force.push_back(u);
    for (int m = 0; m < 1000; ++m) {
      if (v == 0.0) {
        const double net = u - o;
        if (std::abs(net) <= c) continue;
        v += 1e-6 * (net - (net > 0 ? c : -c)) / J;
      } else {
        const double next = v + 1e-6 * (u - o - b * v - (v > 0 ? c : -c)) / J;
        q += 1e-6 * v;
        v = (next > 0) != (v > 0) ? 0.0 : next;
        continue;
      }
      q += 1e-6 * v;
    }
  }
  return log;
}

void OutputErrorCoverage(double rho, int seeds, double low, double high) {
  AxisOeOptions options;
  options.free = {"inertia", "viscous", "coulomb", "offset"};
  AxisSection start;
  start.inertia = 0.08;
  start.viscous = 0.1;
  start.coulomb = 0.5;
  start.offset = 0.0;
  CheckAxisCoverage(
      "OE rho " + std::to_string(rho), seeds,
      [&](unsigned seed) { return FitAxisOutputError({MakeStepAxisLog(rho, 9000u + seed)}, start, nullptr, options).fit; },
      {0.05, 0.2, 1.0, 0.3}, low, high);
}

}  // namespace

// Measured (docs/models.md#axis-output-error): coverage 0.88-0.96, empirical
// / reported std 0.96-1.23 with the rate logged. Position alone covers worse
// (0.83-0.91, std ratio up to 2.6: quantisation errors are constant while
// the axis sticks), which the docs state.
TEST_CASE("axis output error, torque steps, 13-bit encoder, AR(1) rate noise: intervals cover") {
  OutputErrorCoverage(0.9, 100, 0.85, 0.99);
}

namespace {

// Output-error joint: closed-loop joints with sticking motor friction from
// tests/support/reference_joint_friction.h (its own RK4 generator, PI speed
// loop, quantising encoders, AR(1) 0.7 angle noise), 10 s at 1 kHz each,
// started from the inverse-dynamics fit as the command does.
struct JointSamples {
  std::vector<std::pair<std::string, double>> truth;
  std::vector<Sample> samples;
};

JointSamples JointOutputErrorSeeds(unsigned first, unsigned count) {
  const driveid::testing::FrictionJointTruth truth;
  JointSamples out;
  out.truth = {{"motor_inertia", truth.motor_inertia}, {"link_inertia", truth.link_inertia},
               {"stiffness", truth.stiffness},         {"damping", truth.damping},
               {"motor_viscous", truth.motor_viscous}, {"motor_coulomb", truth.motor_coulomb},
               {"link_viscous", truth.link_viscous},   {"offset", truth.offset}};
  out.samples.resize(out.truth.size());
  const JointSection start = driveid::testing::FarJointStart(truth);
  JointFitOptions id_options;
  id_options.per_log = id_options.sensitivity = id_options.refuse_undetermined = false;
  for (unsigned seed = first; seed < first + count; ++seed) {
    driveid::testing::FrictionJointExperiment experiment;
    experiment.seed = seed;
    const JointLog log =
        driveid::testing::ToJointLog(driveid::testing::SimulateFrictionJoint(truth, experiment), "joint_mc.csv");
    const JointFitOutput id = FitJoint({log}, start, id_options);
    const FitResult fit = FitJointOutputError({log}, start, &id.params, {}).fit;
    for (std::size_t j = 0; j < out.truth.size(); ++j) out.samples[j].Add(Find(fit, out.truth[j].first), out.truth[j].second);
  }
  return out;
}

}  // namespace

TEST_CASE("joint output error, closed loop, sticking motor, quantised AR(1) encoders: intervals cover over 50 seeds") {
  // 50 seeds (multiple shooting, the default, costs ~3 s a seed; a noisy
  // measured torque's coverage: tests/fit/joint_oe_coverage_test.cc).
  const JointSamples s = JointOutputErrorSeeds(500, 50);
  for (std::size_t j = 0; j < s.truth.size(); ++j) {
    INFO("joint OE, " << s.truth[j].first << ": empirical / reported std = " << s.samples[j].Ratio()
                      << ", 95 % coverage " << s.samples[j].Coverage());
    CHECK(s.samples[j].Coverage() >= 0.88);
    // Not far too wide (all 50 covered happens 8 % of the time at 95 %).
    CHECK(s.samples[j].Ratio() > 0.7);
  }
}
