// Output-error axis fit (docs/models.md#axis-output-error): the simulator's
// sensitivities against finite differences, recovery from torque steps made
// by the test's own generator, refusals by name.
#include "fit/axis/axis_oe_fit.h"

#include <cmath>
#include <random>
#include <string>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "sim/axis_simulator.h"
#include "support/axis_values.h"

using namespace driveid;
using driveid::testing::AxisValue;

namespace {

// The test's own generator: the axis J v' = u - b v - tau_c sgn v - tau_0
// (optionally per direction), explicit Euler with 1e-5 s steps; at rest it
// sticks while |u - tau_0| is within the Coulomb limit of that side; a step
// that would carry v through 0 ends at rest. Torque held per 1 ms sample.
struct Truth {
  double inertia = 0.05, viscous = 0.2, coulomb = 1.0, offset = 0.3;
  double coulomb_pos = 0.0, coulomb_neg = 0.0;
  double stribeck = 0.0, stribeck_velocity = 1.0;  // excess s exp(-(v/v_s)^2), breakaway c + s
};

AxisLog StepLog(const Truth& p, double quantum, double rate_noise, unsigned seed, bool with_rate) {
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, rate_noise);
  const double steps[][2] = {{0.2, 0.0}, {1.0, 2.0}, {1.0, -2.0}, {0.5, 0.6}, {1.0, -1.6}, {0.8, 1.9}};
  AxisLog log;
  log.path = "steps.csv";
  double q = 0.4, v = 0.0, t = 0.0;
  const int substeps = 100;
  const double dt = 1e-3 / substeps;
  for (const auto& step : steps) {
    const int samples = static_cast<int>(std::lround(step[0] * 1000));
    for (int s = 0; s < samples; ++s) {
      log.time.push_back(t);
      log.position.push_back(quantum > 0 ? quantum * std::round(q / quantum) : q);
      if (with_rate) log.rate.push_back(v + noise(random));
      const double u = step[1];
      log.force.push_back(u);
      for (int m = 0; m < substeps; ++m) {
        const double excess = p.stribeck * std::exp(-(v / p.stribeck_velocity) * (v / p.stribeck_velocity));
        const double forward = p.coulomb + p.coulomb_pos + excess, backward = p.coulomb + p.coulomb_neg + excess;
        if (v == 0.0) {
          const double net = u - p.offset;
          if (net <= forward && net >= -backward) continue;  // sticks
          const double friction = net > 0 ? forward : -backward;
          v += dt * (net - friction) / p.inertia;
        } else {
          const double friction = v > 0 ? forward : -backward;
          const double next = v + dt * (u - p.offset - p.viscous * v - friction) / p.inertia;
          q += dt * v;
          v = (next > 0) != (v > 0) ? 0.0 : next;
          continue;
        }
        q += dt * v;
      }
      t += 1e-3;
    }
  }
  return log;
}

}  // namespace

TEST_CASE("axis simulator: sensitivities match central differences through stick/slip events") {
  AxisParameters p{0.05, 0.2, 1.0, 0.3, 0.4, -0.2, 0.1, 0.05, 0.03, 0.02, {}};
  AxisValue(p, "stribeck") = 0.15;
  AxisValue(p, "stribeck_velocity") = 0.8;
  const AxisLog log = StepLog({}, 0.0, 0.0, 1, false);
  std::vector<int> all;
  for (std::size_t j = 0; j < AxisParameterCount(); ++j) all.push_back(static_cast<int>(j));
  AxisSimulator simulator(all, 1e-12, 1e-10);
  AxisResponse base;
  simulator.Simulate(p, log.time, log.force, 0.4, 0.0, true, &base);
  CHECK(base.switch_count >= 3);  // sticks and reverses
  for (std::size_t j = 0; j < AxisParameterCount(); ++j) {
    const AxisRow& row = AxisTermRow(j);
    const double h = 1e-6 * std::max(1.0, std::abs(ModelValue(row, p)));
    AxisParameters plus = p, minus = p;
    ModelValue(row, plus) += h;
    ModelValue(row, minus) -= h;
    AxisResponse a, b;
    simulator.Simulate(plus, log.time, log.force, 0.4, 0.0, false, &a);
    simulator.Simulate(minus, log.time, log.force, 0.4, 0.0, false, &b);
    double worst = 0.0, scale = 0.0;
    for (std::size_t k = 0; k < log.time.size(); ++k) {
      const double fd = (a.position[k] - b.position[k]) / (2 * h);
      const double analytic = base.position_sensitivity[k * AxisParameterCount() + j];
      worst = std::max(worst, std::abs(fd - analytic));
      scale = std::max(scale, std::abs(fd));
    }
    INFO("term " << j << ": max |fd - analytic| " << worst << " of " << scale);
    CHECK(scale > 0.0);
    CHECK(worst <= 2e-3 * scale);
  }
}

TEST_CASE("axis simulator: the exact per-sample solution agrees with CVODES and with central differences") {
  // A torque that changes every sample (a closed loop's): two sines and a
  // deterministic ripple; the axis sticks, breaks away and reverses.
  AxisLog log;
  for (int k = 0; k < 3000; ++k) {
    const double t = 1e-3 * k;
    log.time.push_back(t);
    log.force.push_back(1.6 * std::sin(2 * M_PI * 1.3 * t) + 0.5 * std::sin(2 * M_PI * 7.1 * t) +
                        0.05 * std::sin(1.7e3 * t * t));
  }
  AxisParameters p{0.05, 0.2, 1.0, 0.3, 0.0, 0.0, 0.1, 0.05, 0.03, 0.02, {}};
  std::vector<int> terms;
  for (const auto member : {&AxisParameters::inertia, &AxisParameters::viscous, &AxisParameters::coulomb,
                            &AxisParameters::offset, &AxisParameters::coulomb_pos, &AxisParameters::coulomb_neg,
                            &AxisParameters::viscous_pos, &AxisParameters::viscous_neg}) {
    terms.push_back(static_cast<int>(AxisIndex(member)));
  }
  AxisSimulator exact(terms, 1e-12, 1e-10), integrated(terms, 1e-12, 1e-10, false);
  AxisResponse e, c;
  exact.Simulate(p, log.time, log.force, 0.4, 0.0, true, &e);
  integrated.Simulate(p, log.time, log.force, 0.4, 0.0, true, &c);
  CHECK(e.switch_count >= 6);
  CHECK(e.switch_count == c.switch_count);
  double q_scale = 0.0, q_worst = 0.0, v_scale = 0.0, v_worst = 0.0;
  for (std::size_t k = 0; k < log.time.size(); ++k) {
    q_scale = std::max(q_scale, std::abs(c.position[k] - 0.4));
    q_worst = std::max(q_worst, std::abs(e.position[k] - c.position[k]));
    v_scale = std::max(v_scale, std::abs(c.rate[k]));
    v_worst = std::max(v_worst, std::abs(e.rate[k] - c.rate[k]));
    REQUIRE(e.mode[k] == c.mode[k]);
  }
  INFO("q: " << q_worst << " of " << q_scale << "; v: " << v_worst << " of " << v_scale);
  CHECK(q_worst <= 1e-6 * q_scale);  // CVODES: relative tolerance 1e-8 per step over 3000 samples
  CHECK(v_worst <= 1e-5 * v_scale);
  const std::size_t np = terms.size();
  for (std::size_t j = 0; j < np; ++j) {
    double AxisParameters::*member = AxisTermRow(static_cast<std::size_t>(terms[j])).in_model;
    const double h = 1e-6 * std::max(1.0, std::abs(p.*member));
    AxisParameters plus = p, minus = p;
    plus.*member += h;
    minus.*member -= h;
    AxisResponse a, b;
    exact.Simulate(plus, log.time, log.force, 0.4, 0.0, false, &a);
    exact.Simulate(minus, log.time, log.force, 0.4, 0.0, false, &b);
    double fd_worst = 0.0, cvodes_worst = 0.0, scale = 0.0;
    for (std::size_t k = 0; k < log.time.size(); ++k) {
      const double fd = (a.position[k] - b.position[k]) / (2 * h);
      const double analytic = e.position_sensitivity[k * np + j];
      fd_worst = std::max(fd_worst, std::abs(fd - analytic));
      cvodes_worst = std::max(cvodes_worst, std::abs(c.position_sensitivity[k * np + j] - analytic));
      scale = std::max(scale, std::abs(fd));
    }
    INFO("term " << terms[j] << ": max |fd - exact| " << fd_worst << ", |cvodes - exact| " << cvodes_worst << " of "
                 << scale);
    CHECK(scale > 0.0);
    CHECK(fd_worst <= 1e-4 * scale);
    CHECK(cvodes_worst <= 1e-4 * scale);
  }
}

TEST_CASE("axis OE: torque steps from an independent generator recover J, b, tau_c, tau_0 with covering intervals") {
  AxisOeOptions options;
  options.free = {"inertia", "viscous", "coulomb", "offset"};
  AxisSection start{0.08, 0.1, 0.5, 0.0, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}};
  int covered = 0, total = 0;
  for (unsigned seed : {1u, 2u, 3u}) {
    const AxisLog log = StepLog({}, 2 * M_PI / 4096, 0.05, seed, true);
    const AxisOeOutput out = FitAxisOutputError({log}, start, nullptr, options);
    CHECK(out.params.inertia == Approx(0.05).epsilon(0.02));
    CHECK(out.params.viscous == Approx(0.2).epsilon(0.02));
    CHECK(out.params.coulomb == Approx(1.0).epsilon(0.02));
    CHECK(out.params.offset == Approx(0.3).epsilon(0.05));
    const double truth[] = {0.05, 0.2, 1.0, 0.3};
    for (std::size_t j = 0; j < 4; ++j) {
      const auto& e = out.fit.estimates[j];
      covered += truth[j] >= e.ci95_low && truth[j] <= e.ci95_high;
      ++total;
    }
    REQUIRE(out.fit.channels.size() == 2);
    CHECK(out.fit.channels[0].fit_percent > 95.0);
  }
  CHECK(covered >= total - 2);
}

TEST_CASE("axis OE: per-direction Coulomb from position alone") {
  Truth truth;
  truth.coulomb = 0.0;
  truth.offset = 0.0;
  truth.coulomb_pos = 1.1;
  truth.coulomb_neg = 0.7;
  const AxisLog log = StepLog(truth, 2 * M_PI / 4096, 0.0, 4, false);
  AxisOeOptions options;
  options.free = {"inertia", "viscous", "coulomb_pos", "coulomb_neg"};
  AxisSection start{0.08, 0.1, {}, {}, {}, {}, 0.5, 0.5, {}, {}, {}, {}, {}, {}, {}};
  const AxisOeOutput out = FitAxisOutputError({log}, start, nullptr, options);
  CHECK(out.params.coulomb_pos == Approx(1.1).epsilon(0.02));
  CHECK(out.params.coulomb_neg == Approx(0.7).epsilon(0.02));
  CHECK(out.params.inertia == Approx(0.05).epsilon(0.02));
  CHECK(out.fit.channels.size() == 1);
}

TEST_CASE("axis OE: one direction of motion cannot separate offset and Coulomb: refused by name") {
  AxisLog log = StepLog({}, 2 * M_PI / 4096, 0.0, 5, false);
  // Keep the first two steps only (rest, then forward).
  log.time.resize(1200);
  log.position.resize(1200);
  log.force.resize(1200);
  AxisOeOptions options;
  options.free = {"inertia", "viscous", "coulomb", "offset"};
  AxisSection start{0.08, 0.1, 0.5, 0.0, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}};
  try {
    FitAxisOutputError({log}, start, nullptr, options);
    FAIL("no refusal");
  } catch (const IdentificationError& e) {
    const std::string message = e.what();
    CHECK(message.find("coulomb") != std::string::npos);
    CHECK(message.find("offset") != std::string::npos);
  }
  CHECK_THROWS_AS(FitAxisOutputError({log}, AxisSection{}, nullptr, options), InputError);  // no inertia start
  CHECK(IsTorqueStepLog(log));
}

TEST_CASE("axis OE: a Stribeck excess and its velocity recovered from torque steps") {
  Truth truth;
  truth.stribeck = 0.3;
  truth.stribeck_velocity = 0.5;
  int covered = 0;
  for (unsigned seed : {6u, 7u, 8u}) {
    const AxisLog log = StepLog(truth, 2 * M_PI / 4096, 0.05, seed, true);
    AxisOeOptions options;
    options.free = {"inertia", "viscous", "coulomb", "offset", "stribeck", "stribeck_velocity"};
    AxisSection start{0.08, 0.1, 0.5, 0.0, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, false};
    AxisValue(start, "stribeck") = 0.1;
    AxisValue(start, "stribeck_velocity") = 1.0;
    const AxisOeOutput out = FitAxisOutputError({log}, start, nullptr, options);
    CHECK(AxisValue(out.params, "stribeck") == Approx(0.3).epsilon(0.05));
    CHECK(AxisValue(out.params, "stribeck_velocity") == Approx(0.5).epsilon(0.05));
    CHECK(out.params.coulomb == Approx(1.0).epsilon(0.02));
    CHECK(out.params.inertia == Approx(0.05).epsilon(0.02));
    for (const auto& e : out.fit.estimates) {
      if (e.name == "stribeck") covered += 0.3 >= e.ci95_low && 0.3 <= e.ci95_high;
    }
  }
  CHECK(covered >= 2);
  // Refusals: the pair needs start values; inverse dynamics cannot fit it.
  AxisOeOptions options;
  options.free = {"inertia", "stribeck"};
  const AxisLog log = StepLog(truth, 2 * M_PI / 4096, 0.05, 9, true);
  AxisSection no_velocity{0.08, 0.2, 1.0, 0.3, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, false};
  AxisValue(no_velocity, "stribeck") = 0.1;
  CHECK_THROWS_WITH(FitAxisOutputError({log}, no_velocity, nullptr, options),
                    Catch::Contains("axis.stribeck_velocity must be > 0"));
}

TEST_CASE("axis OE: repeats are fitted one by one, and one that ran differently is named") {
  AxisOeOptions options;
  options.free = {"inertia", "viscous", "coulomb", "offset"};
  AxisSection start{0.08, 0.1, 0.5, 0.0, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}};
  std::vector<AxisLog> logs;
  for (unsigned seed : {11u, 12u, 13u}) {
    logs.push_back(StepLog({}, 2 * M_PI / 4096, 0.05, seed, true));
    logs.back().path = "repeat" + std::to_string(seed) + ".csv";
  }
  const AxisOeOutput agree = FitAxisOutputError(logs, start, nullptr, options);
  REQUIRE(agree.fit.per_log.size() == 3);
  for (const auto& set : agree.fit.per_log) {
    CHECK(set.failure.empty());
    CHECK(set.estimates.size() == 4);
  }
  for (const auto& w : agree.fit.warnings) CHECK(w.find("logs disagree") == std::string::npos);
  // The third repeat with 30 % more viscous friction (a warmer gearbox).
  Truth warm;
  warm.viscous = 0.26;
  logs[2] = StepLog(warm, 2 * M_PI / 4096, 0.05, 13u, true);
  logs[2].path = "warm.csv";
  const AxisOeOutput differ = FitAxisOutputError(logs, start, nullptr, options);
  bool named = false;
  for (const auto& w : differ.fit.warnings) named = named || w.find("logs disagree: viscous") != std::string::npos;
  INFO(differ.fit.warnings.size() << " warnings");
  CHECK(named);
}
