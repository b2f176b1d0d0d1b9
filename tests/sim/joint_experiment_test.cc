// Synthetic frequency-response experiments on the elastic joint
// (sim/joint_experiment.h), checked against what must hold whatever the
// integrator: momentum (the spring and its damping are internal), the
// multisine's rms and lines, the PI loop's law recomputed from the log, a
// motor held by its Coulomb friction, and refusals naming the option.
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "sim/joint_experiment.h"
#include "support/dft_bin.h"

namespace driveid {
namespace {

JointParameters Joint() {
  JointParameters p;
  p.motor_inertia = 0.8;
  p.link_inertia = 1.5;
  p.stiffness = 400.0;
  p.damping = 0.5;
  return p;
}

TEST_CASE("frictionless: J_m theta_m + J_l theta_l is the double integral of the held torque, to rounding") {
  const double n = 10.0;
  const JointParameters p = Joint();
  JointExperiment e;
  e.duration = 4.0;
  e.amplitude = 0.3;
  e.kp = 0.02;  // closed loop: the torque depends on the state, still held per sample
  e.ki = 0.1;
  e.noise = 0.05;
  const JointExperimentLog log = SimulateJointExperiment(p, n, e);
  REQUIRE(log.t.size() == 4000);
  // P = J_m theta_m + J_l theta_l (link side, theta_m = q_motor / n): P'' = n tau,
  // held over each interval, so P and P' step exactly.
  const double dt = 1.0 / e.rate;
  double position = 0.0, momentum = 0.0, worst = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < log.t.size(); ++k) {
    const double p_log = p.motor_inertia * log.q_motor[k] / n + p.link_inertia * log.q_link[k];
    worst = std::max(worst, std::abs(p_log - position));
    scale = std::max(scale, std::abs(position));
    const double torque = n * log.tau[k];
    position += momentum * dt + 0.5 * torque * dt * dt;
    momentum += torque * dt;
  }
  REQUIRE(scale > 1e-3);
  CHECK(worst < 1e-9 * scale);
}

TEST_CASE("the multisine: rms as asked, periodic, its lines only inside the band") {
  JointExperiment e;
  e.duration = 4.0;
  e.period = 2.0;
  e.f_low = 3.0;
  e.f_high = 20.0;
  e.amplitude = 0.25;
  const JointExperimentLog log = SimulateJointExperiment(Joint(), 5.0, e);
  const std::size_t period = 2000;
  double power = 0.0;
  for (std::size_t k = 0; k < period; ++k) {
    power += log.r[k] * log.r[k];
    CHECK(log.r[k + period] == log.r[k]);
    CHECK(log.tau[k] == log.r[k]);  // open loop
  }
  CHECK(std::sqrt(power / period) == Approx(0.25).epsilon(1e-12));
  // Line l of the period is at l / 2 s: lines 6 .. 40 carry it all.
  double inside = 0.0, outside = 0.0;
  for (int l = 0; l <= 1000; ++l) {
    (l >= 6 && l <= 40 ? inside : outside) += std::norm(testing::DftBin(log.r, period, l));
  }
  CHECK(outside < 1e-20 * inside);
}

TEST_CASE("the PI speed loop: tau = r - kp w - ki (sum of w dt), w the noisy measured speed") {
  JointExperiment e;
  e.duration = 1.0;
  e.period = 0.5;
  e.kp = 0.05;
  e.ki = 0.4;
  e.noise = 0.2;
  const JointExperimentLog log = SimulateJointExperiment(Joint(), 10.0, e);
  double integral = 0.0, worst = 0.0;
  for (std::size_t k = 0; k < log.t.size(); ++k) {
    integral += log.qd_motor[k] / e.rate;
    worst = std::max(worst, std::abs(log.tau[k] - (log.r[k] - e.kp * log.qd_motor[k] - e.ki * integral)));
  }
  CHECK(worst < 1e-12);
}

TEST_CASE("a motor whose Coulomb friction exceeds the torque never moves, nor does the link") {
  JointParameters p = Joint();
  p.motor_coulomb = 2.0;  // link side; the torque is n tau = 10 x 0.1 rms, crest below 2
  JointExperiment e;
  e.duration = 2.0;
  const JointExperimentLog log = SimulateJointExperiment(p, 10.0, e);
  double peak = 0.0;
  for (std::size_t k = 0; k < log.t.size(); ++k) {
    peak = std::max(peak, std::abs(10.0 * log.tau[k]));
    CHECK(log.q_motor[k] == 0.0);
    CHECK(log.q_link[k] == 0.0);
  }
  REQUIRE(peak < 2.0);
  REQUIRE(peak > 0.5);
}

TEST_CASE("refused by the option's name") {
  JointExperiment e;
  e.excitation = "noise";
  CHECK_THROWS_WITH(SimulateJointExperiment(Joint(), 1.0, e), Catch::Contains("‹excitation› noise"));
  e = {};
  e.period = 0.01;  // 10 samples
  CHECK_THROWS_WITH(SimulateJointExperiment(Joint(), 1.0, e), Catch::Contains("‹period›"));
  e = {};
  e.f_high = 600.0;
  CHECK_THROWS_WITH(SimulateJointExperiment(Joint(), 1.0, e), Catch::Contains("‹band›"));
  e = {};
  e.noise = -1.0;
  CHECK_THROWS_AS(SimulateJointExperiment(Joint(), 1.0, e), OptionError);
  JointParameters p = Joint();
  p.link_inertia = 0.0;
  CHECK_THROWS_AS(SimulateJointExperiment(p, 1.0, {}), InputError);
}

}  // namespace
}  // namespace driveid
