// Output-error joint (docs/models.md#joint-output-error): the simulator's
// sensitivities against finite differences through stick-slip events,
// recovery of a closed-loop joint with sticking motor friction from the
// test's own generator (tests/support/reference_joint_friction.h), refusals.
#include "fit/joint/joint_oe_fit.h"

#include <array>
#include <cmath>
#include <string>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "fit/joint/joint_fit.h"
#include "fit/core/fit_statistics.h"
#include "fit/joint/joint_oe_segments.h"
#include "sim/joint_simulator.h"
#include "support/friction_joint_cases.h"

using namespace driveid;
using driveid::testing::FrictionJointExperiment;
using driveid::testing::FrictionJointTruth;

namespace {

using driveid::testing::ToJointLog;

// An estimate within `tolerance` (relative) of the truth and within
// `stds` of its std.
void CheckRecovered(const FitResult& fit, const char* name, double truth, double tolerance, double stds) {
  for (const auto& e : fit.estimates) {
    if (e.name != name) continue;
    INFO(name << " = " << e.value << " +- " << e.standard_error << " [" << e.ci95_low << ", " << e.ci95_high
              << "], truth " << truth);
    CHECK(std::abs(e.value - truth) <= tolerance * truth);
    CHECK(std::abs(e.value - truth) <= stds * e.standard_error);
    return;
  }
  FAIL("no estimate " << name);
}

JointSection StartSection(const FrictionJointTruth& t) {
  JointSection s;
  s.gear_ratio = t.gear_ratio;
  s.motor_inertia = 1.3 * t.motor_inertia;
  s.link_inertia = 0.8 * t.link_inertia;
  s.stiffness = 1.4 * t.stiffness;
  s.damping = 1.0;
  s.motor_viscous = 1.0;
  s.motor_coulomb = 1.0;
  s.link_viscous = 0.0;
  s.link_coulomb = 0.0;
  s.offset = 0.0;
  return s;
}

// Output error on one log, started from the inverse-dynamics fit as the
// command does.
struct OeRun {
  JointFitOutput id;
  JointOeOutput oe;
};
OeRun FitFromInverseDynamics(const JointLog& log, const JointSection& start) {
  JointFitOptions id_options;
  id_options.per_log = id_options.sensitivity = false;
  id_options.refuse_undetermined = false;
  OeRun run{FitJoint({log}, start, id_options), {}};
  run.oe = FitJointOutputError({log}, start, &run.id.params, {});
  return run;
}

}  // namespace

TEST_CASE("joint OE recovers a closed-loop joint with sticking motor friction", "[joint-oe]") {
  const FrictionJointTruth truth;
  FrictionJointExperiment experiment;
  experiment.seed = 3;
  const auto generated = driveid::testing::SimulateFrictionJoint(truth, experiment);
  INFO("sticks " << generated.sticks);
  CHECK(generated.sticks >= 4);
  const OeRun run = FitFromInverseDynamics(ToJointLog(generated, "closed_loop.csv"), StartSection(truth));
  const JointOeOutput& oe = run.oe;
  // One seed: within 3 std (the 95 % intervals' coverage is measured over
  // seeds in tests/fit/calibration_test.cc).
  const auto check = [&](const char* name, double value, double tolerance) {
    CheckRecovered(oe.fit, name, value, tolerance, 3.0);
  };
  check("motor_inertia", truth.motor_inertia, 0.02);
  check("link_inertia", truth.link_inertia, 0.02);
  check("stiffness", truth.stiffness, 0.02);
  check("damping", truth.damping, 0.10);
  check("motor_viscous", truth.motor_viscous, 0.10);
  check("motor_coulomb", truth.motor_coulomb, 0.10);
}

namespace {
JointParameters TruthParameters(const FrictionJointTruth& truth) {
  JointParameters p;
  p.motor_inertia = truth.motor_inertia;
  p.link_inertia = truth.link_inertia;
  p.stiffness = truth.stiffness;
  p.damping = truth.damping;
  p.motor_viscous = truth.motor_viscous;
  p.motor_coulomb = truth.motor_coulomb;
  p.link_viscous = truth.link_viscous;
  p.offset = truth.offset;
  return p;
}
const std::vector<int> kTerms = {kJointMotorInertia, kJointLinkInertia, kJointStiffness, kJointDamping,
                                 kJointMotorViscous, kJointMotorCoulomb, kJointLinkViscous, kJointOffset};
}  // namespace

TEST_CASE("joint simulator: the exact path reproduces the independent generator", "[joint-oe]") {
  // Noise-free, unquantised: the generator's RK4 (200 sub-steps, stops located
  // by interpolation) against the simulator's matrix exponentials.
  const FrictionJointTruth truth;
  FrictionJointExperiment experiment;
  experiment.noise = 0.0;
  experiment.motor_counts = experiment.link_counts = 1e15;
  experiment.substeps = 200;
  const auto g = driveid::testing::SimulateFrictionJoint(truth, experiment);
  REQUIRE(g.sticks >= 10);
  std::vector<double> u;
  for (double t : g.tau) u.push_back(truth.gear_ratio * t);
  JointSimulator exact(kTerms, 1e-12, 1e-9);
  JointStateResponse a;
  exact.Simulate(TruthParameters(truth), g.t, u, {0, 0, 0, 0}, false, &a);
  double motor = 0.0, link = 0.0;
  for (std::size_t k = 0; k < g.t.size(); ++k) {
    motor = std::max(motor, std::abs(a.state[4 * k] - g.q_motor[k] / truth.gear_ratio));
    link = std::max(link, std::abs(a.state[4 * k + 2] - g.q_link[k]));
  }
  INFO("worst motor " << motor << " rad, link " << link << " rad");
  CHECK(motor < 1e-8);
  CHECK(link < 1e-8);
}

TEST_CASE("joint simulator: exact path, integrator and finite differences agree through stick-slip", "[joint-oe]") {
  const FrictionJointTruth truth;
  FrictionJointExperiment experiment;
  experiment.duration = 3.0;
  const auto g = driveid::testing::SimulateFrictionJoint(truth, experiment);
  const JointParameters p = TruthParameters(truth);
  std::vector<double> u;
  for (double t : g.tau) u.push_back(truth.gear_ratio * t);
  // A moving start, so that every initial state matters (a stuck motor's start rate does not).
  const std::array<double, 4> x0 = {0.01, 0.5, 0.0, 0.2};
  std::vector<int> terms = kTerms;
  for (int t : {kJointInitialMotorAngle, kJointInitialMotorRate, kJointInitialLinkAngle, kJointInitialLinkRate}) {
    terms.push_back(t);
  }
  JointSimulator exact(terms, 1e-12, 1e-9), integrated(terms, 1e-12, 1e-9);
  integrated.set_use_integrator(true);
  JointStateResponse a, b;
  exact.Simulate(p, g.t, u, x0, true, &a);
  integrated.Simulate(p, g.t, u, x0, true, &b);
  REQUIRE(a.switch_count >= 4);
  CHECK(a.switch_count == b.switch_count);
  // States: the integrator agrees to 1e-3 of the deflection's scale (its tolerances).
  double worst = 0.0, deflection = 0.0;
  for (std::size_t i = 0; i < a.state.size(); ++i) worst = std::max(worst, std::abs(a.state[i] - b.state[i]));
  for (std::size_t k = 0; k < g.t.size(); ++k) {
    deflection = std::max(deflection, std::abs(a.state[4 * k] - a.state[4 * k + 2]));
  }
  INFO("deflection up to " << deflection << " rad");
  CHECK(worst < 1e-3 * deflection);
  // Sensitivities of the link angle: exact path vs integrator vs central differences.
  const std::size_t np = terms.size(), samples = g.t.size();
  for (std::size_t j = 0; j < np; ++j) {
    JointParameters up = p, down = p;
    std::array<double, 4> x_up = x0, x_down = x0;
    const int state = InitialStateIndex(terms[j]);
    double h = 1e-6;
    if (state < 0) {
      const double value = p.*(JointParameterTable()[terms[j]].in_model);
      h = 1e-5 * std::max(std::abs(value), 1e-3);
      up.*(JointParameterTable()[terms[j]].in_model) += h;
      down.*(JointParameterTable()[terms[j]].in_model) -= h;
    } else {
      x_up[static_cast<std::size_t>(state)] += h;
      x_down[static_cast<std::size_t>(state)] -= h;
    }
    JointStateResponse ru, rd;
    exact.Simulate(up, g.t, u, x_up, false, &ru);
    exact.Simulate(down, g.t, u, x_down, false, &rd);
    double scale = 0.0, error_fd = 0.0, error_integrator = 0.0;
    for (std::size_t k = 0; k < samples; ++k) {
      for (int i : {0, 2}) {
        const double s = a.sensitivity[(k * np + j) * 4 + i];
        const double fd = (ru.state[4 * k + i] - rd.state[4 * k + i]) / (2.0 * h);
        scale = std::max(scale, std::abs(s));
        error_fd = std::max(error_fd, std::abs(s - fd));
        error_integrator = std::max(error_integrator, std::abs(s - b.sensitivity[(k * np + j) * 4 + i]));
      }
    }
    INFO("term " << terms[j] << ": scale " << scale << ", fd error " << error_fd
                 << ", integrator error " << error_integrator);
    CHECK(error_fd < 1e-3 * scale);
    CHECK(error_integrator < 1e-3 * scale);
  }
}

TEST_CASE("joint OE by multiple shooting recovers a closed-loop joint from a noisy measured torque", "[joint-oe]") {
  // The torque logged with AR(1) noise (0.02 N m on the motor shaft, 2.4 % of
  // its RMS, as a current-based torque reads): simulated whole from it, the
  // free joint drifts; cut into segments it does not.
  const FrictionJointTruth truth;
  FrictionJointExperiment experiment;
  experiment.seed = 3;
  experiment.torque_noise = 0.02;
  experiment.torque_noise_ar = 0.5;
  const auto generated = driveid::testing::SimulateFrictionJoint(truth, experiment);
  const OeRun run = FitFromInverseDynamics(ToJointLog(generated, "closed_loop_noisy_torque.csv"), StartSection(truth));
  const JointOeOutput& oe = run.oe;
  // Auto: 4 periods of the start's resonance (about 12 Hz here) is 0.34 s:
  // at most 24 segments, 0.42 s, for this 10 s log.
  INFO("segments " << oe.segments << " of " << oe.segment_seconds << " s");
  CHECK(oe.segments >= 20);
  CHECK(oe.segments <= 24);
  bool said = false;
  for (const auto& note : oe.fit.notes) said = said || note.find("multiple shooting") != std::string::npos;
  CHECK(said);
  // The 95 % interval: the coverage test (joint_oe_coverage_test.cc) runs 40 seeds.
  const auto check = [&](const char* name, double value, double tolerance) {
    CheckRecovered(oe.fit, name, value, tolerance, StudentT975(static_cast<int>(oe.segments) - 1));
  };
  check("motor_inertia", truth.motor_inertia, 0.02);
  check("link_inertia", truth.link_inertia, 0.02);
  check("stiffness", truth.stiffness, 0.02);
  check("damping", truth.damping, 0.10);
  CHECK(oe.fit.warnings.empty());
}

TEST_CASE("multiple-shooting segments: lengths, start states", "[joint-oe]") {
  JointLog log;
  for (int k = 0; k < 1000; ++k) {
    const double t = 0.001 * k;
    log.time.push_back(t);
    log.motor_position.push_back(k < 500 ? 10.0 : 10.0 + 20.0 * (t - 0.5));  // at rest, then 20 rad/s
    log.link_position.push_back(1.0 + 2.0 * t);
  }
  JointParameters p;
  p.motor_inertia = 0.5;
  p.link_inertia = 1.5;
  p.stiffness = 2000.0;  // resonance sqrt(2000 * 8/3) = 73.0 rad/s: 4 periods 0.344 s
  CHECK(AutoSegmentSeconds({log}, p) == Approx(4.0 * 2.0 * M_PI / std::sqrt(2000.0 * (2.0 + 2.0 / 3.0))));
  CHECK(SegmentSamples(log, AutoSegmentSeconds({log}, p)) == 345);
  // A long log: at most kMaxAutoSegments segments.
  JointLog long_log = log;
  long_log.time.back() = 100.0;
  CHECK(AutoSegmentSeconds({long_log}, p) == Approx(100.0 / kMaxAutoSegments));
  p.stiffness = 0.0;  // no resonance: single shooting
  CHECK(std::isinf(AutoSegmentSeconds({log}, p)));
  CHECK(SegmentSamples(log, 0.1) == 100);
  CHECK(SegmentSamples(log, 0.01) == kMinSegmentSamples);
  CHECK(SegmentSamples(log, HUGE_VAL) == 1000);
  CHECK(SegmentSamples(log, 5.0) == 1000);
  const std::vector<double> torque(1000, 0.0);
  const auto segments = SplitLog(log, torque, 10.0, 300);
  REQUIRE(segments.size() == 3);
  CHECK(segments[0].begin == 0);
  CHECK(segments[2].end == 1000);
  CHECK(segments[1].begin == segments[0].end);
  CHECK(segments[1].time.size() == segments[1].end - segments[1].begin);
  // The first segment's motor is at rest: its start rate stays 0, not fitted.
  CHECK_FALSE(segments[0].motor_moving);
  CHECK(segments[0].x0[1] == 0.0);
  // The last moves at 20 rad/s on the motor shaft: 2 rad/s link side.
  CHECK(segments[2].motor_moving);
  CHECK(segments[2].x0[1] == Approx(2.0).epsilon(1e-9));
  CHECK(segments[2].x0[0] == Approx(log.motor_position[segments[2].begin] / 10.0));
  CHECK(segments[2].x0[3] == Approx(2.0).epsilon(1e-9));
}
