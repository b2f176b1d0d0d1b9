// The stick/slip simulator against closed forms, finite differences and the
// defining property of sticking friction.
#include "sim/drivetrain_simulator.h"

#include <cmath>

#include <catch2/catch.hpp>

#include "support/paper000.h"

using namespace driveid;

namespace {
using testing_support::PaperDriveTrain;

struct StepLog {
  std::vector<double> time, torque;
};

StepLog MakeStep(double rate, double duration, double step_time, double amplitude) {
  StepLog log;
  const int n = static_cast<int>(std::lround(duration * rate)) + 1;
  for (int k = 0; k < n; ++k) {
    log.time.push_back(k / rate);
    log.torque.push_back(k / rate >= step_time - 1e-12 ? amplitude : 0.0);
  }
  return log;
}
}  // namespace

TEST_CASE("reduced step response matches the closed form, then sticks") {
  const auto params = PaperDriveTrain();
  const auto log = MakeStep(1000.0, 0.2, 0.0, -0.8);
  const auto integration = GENERATE(DriveTrainIntegration::kCvodes, DriveTrainIntegration::kExact);
  INFO("integration " << static_cast<int>(integration));
  DriveTrainSimulator simulator(DriveTrainModel::kReduced, params, {});
  simulator.set_integration(integration);
  DriveTrainResponse response;
  simulator.Simulate(params, log.time, log.torque, false, &response);
  // Sliding in the negative direction: target level Y = n_g u + tau_c.
  const auto tf = CalcReducedTransferFunction(params);
  const double zeta = tf.damping_ratio, wn = tf.natural_frequency;
  const double wd = wn * std::sqrt(1 - zeta * zeta);
  const double target = 80.0 * -0.8 + params.coulomb_friction;
  const double stick_time = M_PI / wd;
  const double stuck_level = target * (1 + std::exp(-zeta * wn * stick_time));
  for (std::size_t k = 0; k < log.time.size(); ++k) {
    const double t = log.time[k];
    const double expected = t < stick_time ? target * (1 - std::exp(-zeta * wn * t) *
                                                               (std::cos(wd * t) + zeta / std::sqrt(1 - zeta * zeta) * std::sin(wd * t)))
                                           : stuck_level;
    INFO("t = " << t);
    CHECK(response.link_torque[k] == Approx(expected).margin(1e-5));
  }
  CHECK(response.switch_count == 1);
  CHECK(response.friction_mode.back() == 0);
  // Steady state falls short of n_g |u| by about tau_c.
  CHECK(std::abs(response.link_torque.back()) == Approx(64.0 - 5.0).margin(0.25));
}

TEST_CASE("a stuck drive stays put under sub-breakaway torque") {
  auto params = PaperDriveTrain();
  const auto integration = GENERATE(DriveTrainIntegration::kCvodes, DriveTrainIntegration::kExact);
  INFO("integration " << static_cast<int>(integration));
  for (auto model : {DriveTrainModel::kReduced, DriveTrainModel::kFull}) {
    // n_g |u| = 4.8 N m < tau_c = 5 N m: nothing may move, ever.
    const auto log = MakeStep(1000.0, 1.0, 0.1, 0.06);
    DriveTrainSimulator simulator(model, params, {});
    simulator.set_integration(integration);
    DriveTrainResponse response;
    simulator.Simulate(params, log.time, log.torque, false, &response);
    for (double y : response.link_torque) CHECK(y == 0.0);
    CHECK(response.switch_count == 0);
  }
  // After a real step the drive sticks and then holds without creeping.
  const auto log = MakeStep(1000.0, 2.0, 0.02, -0.8);
  DriveTrainSimulator simulator(DriveTrainModel::kReduced, params, {});
  simulator.set_integration(integration);
  DriveTrainResponse response;
  simulator.Simulate(params, log.time, log.torque, false, &response);
  const double at_half = response.link_torque[500];
  CHECK(response.link_torque.back() == at_half);
}

TEST_CASE("sensitivities match central differences of whole simulations") {
  const auto params = PaperDriveTrain();
  struct Case {
    DriveTrainModel model;
    double rate;
    SimulationTolerances tolerances;
    double difference_step;  // relative FD step: above the integrator's noise
    double agreement;        // relative to the largest sensitivity
  };
  const SimulationTolerances tight{1e-10, 1e-9};
  // (the exact path is exact: its differences need only a small step)
  const auto integration = GENERATE(DriveTrainIntegration::kCvodes, DriveTrainIntegration::kExact);
  INFO("integration " << static_cast<int>(integration));
  for (const Case c : {Case{DriveTrainModel::kReduced, 1000.0, tight, 1e-5, 2e-4},
                       Case{DriveTrainModel::kFull, 5000.0, tight, 1e-5, 2e-4},
                       Case{DriveTrainModel::kReduced, 1000.0, {}, 1e-3, 5e-3},
                       Case{DriveTrainModel::kFull, 5000.0, {}, 1e-3, 5e-3}}) {
    // A step followed by a reversal exercises stick, break-away and reversal.
    auto log = MakeStep(c.rate, 0.3, 0.02, -0.8);
    for (std::size_t k = 0; k < log.time.size(); ++k) {
      if (log.time[k] >= 0.15) log.torque[k] = 0.5;
    }
    std::vector<DriveTrainParameter> parameters = {
        DriveTrainParameter::kViscousFriction, DriveTrainParameter::kMotorInertia,
        DriveTrainParameter::kCoulombFriction, DriveTrainParameter::kLinkStiffness,
        DriveTrainParameter::kGearboxStiffness};
    if (c.model == DriveTrainModel::kFull) parameters.push_back(DriveTrainParameter::kGearboxInertia);
    DriveTrainSimulator simulator(c.model, params, parameters, c.tolerances);
    simulator.set_integration(integration);
    DriveTrainResponse response;
    simulator.Simulate(params, log.time, log.torque, true, &response);
    CHECK(response.switch_count >= 2);
    const std::size_t p = parameters.size();
    for (std::size_t j = 0; j < p; ++j) {
      const double value = GetDriveTrainParameter(params, parameters[j]);
      const double h = c.difference_step * value;
      auto plus = params, minus = params;
      SetDriveTrainParameter(plus, parameters[j], value + h);
      SetDriveTrainParameter(minus, parameters[j], value - h);
      DriveTrainResponse rp, rm;
      simulator.Simulate(plus, log.time, log.torque, false, &rp);
      simulator.Simulate(minus, log.time, log.torque, false, &rm);
      double worst = 0.0, scale = 0.0;
      for (std::size_t k = 0; k < log.time.size(); ++k) {
        const double fd = (rp.link_torque[k] - rm.link_torque[k]) / (2 * h);
        worst = std::max(worst, std::abs(fd - response.link_torque_sensitivity[k * p + j]));
        scale = std::max(scale, std::abs(fd));
      }
      INFO("model " << static_cast<int>(c.model) << " parameter " << DriveTrainParameterKey(parameters[j])
                    << " worst " << worst << " scale " << scale);
      CHECK(scale > 0.0);
      CHECK(worst <= c.agreement * scale);
    }
  }
}

TEST_CASE("simulated in pieces (Start, Advance) = simulated at once, bit for bit, across steps and switches") {
  const auto params = PaperDriveTrain();
  // Torque steps up and back down: sliding, sticking and breaking away again.
  StepLog log = MakeStep(2000.0, 0.3, 0.01, -0.8);
  for (std::size_t k = 0; k < log.time.size(); ++k) {
    if (log.time[k] >= 0.15) log.torque[k] = 0.3;
  }
  const std::vector<DriveTrainParameter> free{DriveTrainParameter::kViscousFriction,
                                              DriveTrainParameter::kCoulombFriction};
  const auto integration = GENERATE(DriveTrainIntegration::kCvodes, DriveTrainIntegration::kExact);
  INFO("integration " << static_cast<int>(integration));
  for (auto model : {DriveTrainModel::kReduced, DriveTrainModel::kFull}) {
    DriveTrainSimulator whole(model, params, free), pieces(model, params, free);
    whole.set_integration(integration);
    pieces.set_integration(integration);
    DriveTrainResponse all, part;
    whole.Simulate(params, log.time, log.torque, true, &all);
    REQUIRE(all.switch_count >= 2);
    pieces.Start(params, log.time, log.torque, true);
    std::vector<double> torque, sensitivity, angle;
    const std::size_t end = log.time.size() - 1;
    for (std::size_t last : {std::size_t{0}, std::size_t{1}, std::size_t{37}, std::size_t{300}, std::size_t{301}, end}) {
      CHECK(pieces.next_sample() == torque.size());
      pieces.Advance(last, &part);
      CHECK(part.link_torque.size() == last + 1 - torque.size());
      torque.insert(torque.end(), part.link_torque.begin(), part.link_torque.end());
      sensitivity.insert(sensitivity.end(), part.link_torque_sensitivity.begin(), part.link_torque_sensitivity.end());
      angle.insert(angle.end(), part.motor_angle.begin(), part.motor_angle.end());
    }
    CHECK(part.switch_count == all.switch_count);
    CHECK(torque == all.link_torque);
    CHECK(sensitivity == all.link_torque_sensitivity);
    CHECK(angle == all.motor_angle);
    pieces.Advance(end, &part);  // nothing left
    CHECK(part.link_torque.empty());
  }
}

namespace {
// A torque that changes at every sample (a sum of sines with reversals
// large enough to break the drive away, stick it and reverse it).
StepLog MakeVarying(double rate, double duration) {
  StepLog log;
  const int n = static_cast<int>(std::lround(duration * rate)) + 1;
  for (int k = 0; k < n; ++k) {
    const double t = k / rate;
    log.time.push_back(t);
    log.torque.push_back(0.5 * std::sin(2 * M_PI * 3.1 * t) + 0.25 * std::sin(2 * M_PI * 17.3 * t + 1.0) +
                         0.1 * std::sin(2 * M_PI * 61.0 * t + 2.0));
  }
  return log;
}
}  // namespace

TEST_CASE("a torque that changes every sample: the exact path agrees with CVODES and is the default") {
  const auto params = PaperDriveTrain();
  const std::vector<DriveTrainParameter> free{DriveTrainParameter::kViscousFriction,
                                              DriveTrainParameter::kMotorInertia,
                                              DriveTrainParameter::kCoulombFriction};
  const SimulationTolerances tight{1e-10, 1e-9};
  for (auto model : {DriveTrainModel::kReduced, DriveTrainModel::kFull}) {
    INFO("model " << static_cast<int>(model));
    const auto log = MakeVarying(5000.0, 0.6);
    DriveTrainSimulator cvodes(model, params, free, tight), exact(model, params, free), by_default(model, params, free);
    cvodes.set_integration(DriveTrainIntegration::kCvodes);
    exact.set_integration(DriveTrainIntegration::kExact);
    DriveTrainResponse a, b, c;
    cvodes.Simulate(params, log.time, log.torque, true, &a);
    exact.Simulate(params, log.time, log.torque, true, &b);
    by_default.Simulate(params, log.time, log.torque, true, &c);
    REQUIRE(a.switch_count >= 4);  // sticks and breaks away several times
    CHECK(b.switch_count == a.switch_count);
    double scale = 0.0, worst = 0.0;
    for (std::size_t k = 0; k < log.time.size(); ++k) {
      scale = std::max(scale, std::abs(a.link_torque[k]));
      worst = std::max(worst, std::abs(a.link_torque[k] - b.link_torque[k]));
    }
    CHECK(scale > 10.0);
    CHECK(worst <= 1e-6 * scale);
    for (std::size_t j = 0; j < free.size(); ++j) {
      double s_scale = 0.0, s_worst = 0.0;
      for (std::size_t k = 0; k < log.time.size(); ++k) {
        const std::size_t i = k * free.size() + j;
        s_scale = std::max(s_scale, std::abs(a.link_torque_sensitivity[i]));
        s_worst = std::max(s_worst, std::abs(a.link_torque_sensitivity[i] - b.link_torque_sensitivity[i]));
      }
      INFO("parameter " << DriveTrainParameterKey(free[j]) << " worst " << s_worst << " scale " << s_scale);
      CHECK(s_worst <= 1e-4 * s_scale);
    }
    // The default is the exact path, bit for bit, here and on a stepped log.
    CHECK(c.link_torque == b.link_torque);
    CHECK(c.link_torque_sensitivity == b.link_torque_sensitivity);
    const auto steps = MakeStep(5000.0, 0.3, 0.02, -0.8);
    DriveTrainSimulator stepped(model, params, free), stepped_exact(model, params, free);
    stepped_exact.set_integration(DriveTrainIntegration::kExact);
    stepped_exact.Simulate(params, steps.time, steps.torque, true, &a);
    stepped.Simulate(params, steps.time, steps.torque, true, &c);
    CHECK(c.link_torque == a.link_torque);
  }
}
