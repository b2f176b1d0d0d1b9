// The C-drive plant against closed forms and sticking, the controller's
// eq. (31), the reading of K_I, and simulate -> fit round trips.
#include <cmath>

#include <catch2/catch.hpp>

#include "support/paper001.h"

#include "control/cdrive_controller.h"
#include "fit/cdrive/cdrive_fit.h"
#include "sim/cdrive_closed_loop.h"
#include "sim/cdrive_plant.h"

using namespace driveid;

namespace {
using testing_support::TableOneCDrive;

// Runs the plant from rest with a constant torque, returns the rates at `time`.
Vector2 RatesAfter(const Vector2& torque, double time) {
  CDrivePlant plant(TableOneCDrive());
  plant.Reset({});
  const int steps = 100;
  for (int k = 0; k < steps; ++k) plant.Advance(k * time / steps, (k + 1) * time / steps, torque);
  return plant.state().rate;
}
}  // namespace

TEST_CASE("plant: pure rotation and pure translation follow their closed forms") {
  const auto p = TableOneCDrive();
  const double a = CalcInertiaDiagonal(p), b = CalcInertiaOffDiagonal(p);
  const double t = 0.3, torque = 0.5;
  // Rotation: equal torques, the collar sticks on the screws:
  // (a + b) w' + beta w + delta = tau.
  const Vector2 rotation = RatesAfter({torque, torque}, t);
  const double w_rot = (torque - p.coulomb_motor) / p.viscous_motor * (1 - std::exp(-p.viscous_motor * t / (a + b)));
  CHECK(rotation[0] == Approx(w_rot).epsilon(1e-6));
  CHECK(rotation[1] == Approx(w_rot).epsilon(1e-6));
  // Translation: opposite torques: (a - b) w' + (beta + gamma) w + delta + eta = tau.
  const Vector2 translation = RatesAfter({torque, -torque}, t);
  const double damping = p.viscous_motor + p.viscous_collar;
  const double w_tr = (torque - p.coulomb_motor - p.coulomb_collar) / damping * (1 - std::exp(-damping * t / (a - b)));
  CHECK(translation[0] == Approx(w_tr).epsilon(1e-6));
  CHECK(translation[1] == Approx(-w_tr).epsilon(1e-6));
}

TEST_CASE("plant: torques inside the friction cone move nothing; just outside they do") {
  const auto p = TableOneCDrive();
  // Motor L alone at 0.2 N m: a collar force f in [0.2 - delta, 0.2 + delta] n [-delta, delta] n [-eta, eta]
  // = [0.0914, 0.1086] lets motor R's friction hold everything: nothing moves.
  CHECK(RatesAfter({0.2, 0.0}, 0.2)[0] == 0.0);
  CHECK(RatesAfter({0.1, -0.1}, 0.2)[0] == 0.0);  // translation below delta + eta
  CHECK(RatesAfter({0.1, 0.1}, 0.2)[0] == 0.0);   // rotation below delta
  CHECK(RatesAfter({0.3, -0.3}, 0.2)[0] > 0.0);   // translation above delta + eta = 0.2587
  CHECK(RatesAfter({0.12, 0.12}, 0.2)[0] > 0.0);  // rotation above delta = 0.1086
  // Motor L alone at 0.5 N m exceeds 2 delta = 0.217 N m: it slides.
  const Vector2 one = RatesAfter({0.5, 0.0}, 0.2);
  CHECK(one[0] > 0.0);
  // Dissipation: after the torque is removed everything comes to rest.
  CDrivePlant plant(p);
  plant.Reset({});
  for (int k = 0; k < 100; ++k) plant.Advance(k * 1e-3, (k + 1) * 1e-3, {0.5, -0.2});
  for (int k = 100; k < 2000; ++k) plant.Advance(k * 1e-3, (k + 1) * 1e-3, {0.0, 0.0});
  CHECK(plant.state().rate[0] == 0.0);
  CHECK(plant.state().rate[1] == 0.0);
  CHECK(plant.stuck()[0]);
  CHECK(plant.stuck()[2]);
}

TEST_CASE("plant: coming to rest late in a long run (t ~ 500 s), a translation sticks instead of chattering") {
  // The root finder places the stop to ~100 ulp of t; at t = 524 s the rate
  // left there was above the zero threshold and the contacts flipped
  // direction at every event (found simulating 80 translation cycles); here
  // t = 1e6 s made it happen every time.
  for (double start : {0.0, 524.0, 1e5, 1e6}) {
    CDrivePlant plant(TableOneCDrive());
    plant.Reset({{0.0, 0.0}, {0.05, -0.05}});
    const Vector2 torque{-0.116, 0.116};  // decelerates; inside delta + eta, so it holds
    for (int k = 0; k < 200; ++k) REQUIRE_NOTHROW(plant.Advance(start + k * 1e-3, start + (k + 1) * 1e-3, torque));
    INFO("start " << start << " s");
    CHECK(plant.state().rate[0] == 0.0);
    CHECK(plant.state().rate[1] == 0.0);
    CHECK(plant.stuck() == std::array<bool, 3>{true, true, true});
    CHECK(plant.switch_count() < 10);
  }
}

TEST_CASE("eq. (31): viscous and Coulomb terms, dead zone and rate limit") {
  const auto p = TableOneCDrive();
  FrictionCompensator compensator(p, 0.5, 50.0, 0.001);
  // Far from zero and after the rate limiter has settled: eq. (31) exactly.
  Vector2 tau = Vector2::Zero();
  for (int k = 0; k < 100; ++k) tau = compensator.Update(5.0, -3.0);
  CHECK(tau[0] == Approx(p.viscous_motor * 5 + p.coulomb_motor + 0.5 * p.viscous_collar * 8 + p.coulomb_collar));
  CHECK(tau[1] == Approx(p.viscous_motor * -3 - p.coulomb_motor - 0.5 * p.viscous_collar * 8 - p.coulomb_collar));
  // Inside the dead zone the Coulomb terms head to 0, at most 50/s * 1 ms = 0.05 per period.
  const Vector2 next = compensator.Update(0.1, 0.1);
  CHECK(next[0] == Approx(p.viscous_motor * 0.1 + p.coulomb_motor * 0.95 + p.coulomb_collar * 0.95));
  CHECK(QuantizeEncoder(1.0, 8192) <= 1.0);
  CHECK(1.0 - QuantizeEncoder(1.0, 8192) < 2 * M_PI / 8192);
}

TEST_CASE("reading K_I: the PD reading reproduces the seed's end-point errors, the PI reading does not") {
  const auto p = TableOneCDrive();
  for (const char* name : {"translation", "rotation", "helical"}) {
    ClosedLoopOptions options;
    options.program = TableTwoProgram(name, 1.0);  // 0.5 Hz as in the seed
    CDriveControlSettings pd;
    pd.law = ControlLaw::kPD;
    const auto with_pd = SimulateClosedLoop(p, pd, options);
    INFO(name << ": PD end-point u " << with_pd.endpoint_translation_error << " m, theta "
              << with_pd.endpoint_rotation_error << " rad");
    CHECK(with_pd.endpoint_translation_error < 1e-4);
    CHECK(with_pd.endpoint_rotation_error < 0.01);
    CDriveControlSettings pi;
    pi.law = ControlLaw::kPI;
    const auto with_pi = SimulateClosedLoop(p, pi, options);
    INFO("PI end-point u " << with_pi.endpoint_translation_error << " m, theta " << with_pi.endpoint_rotation_error);
    CHECK((with_pi.endpoint_translation_error > 1e-4 || with_pi.endpoint_rotation_error > 0.01));
  }
}

TEST_CASE("simulate -> friction and simulate -> inertia round trips recover the simulated values") {
  const auto truth = TableOneCDrive();
  CDriveControlSettings settings;
  settings.law = ControlLaw::kPD;
  std::vector<CDriveLog> slow, fast;
  std::uint64_t seed = 1;
  for (const char* name : {"translation", "rotation", "helical"}) {
    ClosedLoopOptions options;
    options.program = TableTwoProgram(name, 4.0);
    options.cycles = 2;
    options.torque_noise = 0.01;
    options.seed = seed++;
    slow.push_back(SimulateClosedLoop(truth, settings, options).log);
    options.program = TableTwoProgram(name, 0.25);
    options.cycles = 3;
    options.seed = seed++;
    fast.push_back(SimulateClosedLoop(truth, settings, options).log);
  }
  auto start = truth;
  start.viscous_motor *= 2.5;
  start.viscous_collar /= 2.0;
  start.coulomb_motor *= 3.0;
  start.coulomb_collar /= 2.5;
  const auto friction = FitCDriveFriction(slow, MakeSection(CDriveParameterTable(), start), {});
  CHECK(*friction.section.viscous_motor == Approx(truth.viscous_motor).epsilon(0.03));
  CHECK(*friction.section.viscous_collar == Approx(truth.viscous_collar).epsilon(0.03));
  CHECK(*friction.section.coulomb_motor == Approx(truth.coulomb_motor).epsilon(0.03));
  CHECK(*friction.section.coulomb_collar == Approx(truth.coulomb_collar).epsilon(0.03));

  auto inertia_start = truth;
  inertia_start.hub_inertia *= 2.5;
  inertia_start.collar_inertia /= 3.0;
  CDriveFitOptions options;
  options.half_window = 0.005;
  const auto inertia = FitCDriveInertia(fast, MakeSection(CDriveParameterTable(), inertia_start), options);
  CHECK(*inertia.section.hub_inertia == Approx(truth.hub_inertia).epsilon(0.05));
  CHECK(*inertia.section.collar_inertia == Approx(truth.collar_inertia).epsilon(0.05));
}
