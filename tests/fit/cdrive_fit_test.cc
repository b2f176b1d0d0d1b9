// C-drive identification against logs of the independent generator with the
// Table I values (docs/reproduction.md): friction from slow programs within 3 %, inertia
// from fast programs within 5 %, refusals naming what cannot be determined.
#include "fit/cdrive/cdrive_fit.h"

#include <cmath>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "support/paper001.h"
#include "support/reference_cdrive.h"

using namespace driveid;

namespace {
CDriveLog Convert(const reference::CDriveLog& log, const std::string& name) {
  return {name, log.t, log.psi_L, log.psi_R, log.tau_L, log.tau_R};
}

std::vector<CDriveLog> Programs(double stroke, int cycles, unsigned seed, bool with_rotation_only = false) {
  const reference::CDrive truth;
  std::vector<CDriveLog> logs;
  if (!with_rotation_only) {
    logs.push_back(Convert(reference::SimulateProgram(truth, 20, -20, stroke, cycles, 1000, 0.01, seed), "translation"));
  }
  logs.push_back(Convert(reference::SimulateProgram(truth, 20, 20, stroke, cycles, 1000, 0.01, seed + 1), "rotation"));
  if (!with_rotation_only) {
    logs.push_back(Convert(reference::SimulateProgram(truth, 14, -28, stroke, cycles, 1000, 0.01, seed + 2), "helical"));
  }
  return logs;
}

CDriveParameters Start() {
  CDriveParameters p = testing_support::TableOneCDrive();  // inertia known; friction guesses 2-3x off
  p.viscous_motor = 0.002655 * 2.5;
  p.viscous_collar = 0.004333 / 2.0;
  p.coulomb_motor = 0.1086 * 3.0;
  p.coulomb_collar = 0.1501 / 2.5;
  return p;
}

CDriveSection Given(const CDriveParameters& p) { return MakeSection(CDriveParameterTable(), p); }

double Estimate(const FitResult& fit, const std::string& name) {
  for (const auto& e : fit.estimates) {
    if (e.name == name) return e.value;
  }
  FAIL("no estimate " << name);
  return 0.0;
}
}  // namespace

TEST_CASE("friction: Table I recovered within 3 % from slow programs") {
  for (unsigned seed : {1u, 10u}) {
    const auto out = FitCDriveFriction(Programs(4.0, 2, seed), Given(Start()), {});
    const reference::CDrive truth;
    for (const auto& e : out.fit.estimates) {
      const double value = e.name == "beta" ? truth.beta : e.name == "gamma" ? truth.gamma
                           : e.name == "delta" ? truth.delta : truth.eta;
      INFO(e.name << " = " << e.value << " +- " << e.standard_error << ", truth " << value << ", seed " << seed);
      CHECK(std::abs(e.value / value - 1.0) < 0.03);
      CHECK(std::abs(e.value - value) < 4.0 * e.standard_error + 0.005 * value);
    }
    CHECK(out.fit.estimates.size() == 4);
    CHECK(out.rows_used > 0.8 * out.rows_possible);
  }
}

TEST_CASE("friction: traces only when asked; the fit is the same without them") {
  const auto logs = Programs(4.0, 2, 4);
  CDriveFitOptions without;
  without.traces = false;
  const auto with_traces = FitCDriveFriction(logs, Given(Start()), {});
  const auto no_traces = FitCDriveFriction(logs, Given(Start()), without);
  REQUIRE(with_traces.traces.size() == logs.size());
  CHECK(with_traces.traces[0].time.size() > 0.9 * logs[0].time.size());
  CHECK(no_traces.traces.empty());
  REQUIRE(no_traces.fit.estimates.size() == with_traces.fit.estimates.size());
  for (std::size_t j = 0; j < no_traces.fit.estimates.size(); ++j) {
    CHECK(no_traces.fit.estimates[j].value == with_traces.fit.estimates[j].value);
    CHECK(no_traces.fit.estimates[j].standard_error == with_traces.fit.estimates[j].standard_error);
  }
  CHECK(no_traces.rows_used == with_traces.rows_used);
}

TEST_CASE("friction: rotation alone is refused naming gamma and eta") {
  try {
    FitCDriveFriction(Programs(4.0, 2, 3, true), Given(Start()), {});
    FAIL("fitted gamma and eta from pure rotation");
  } catch (const IdentificationError& e) {
    const std::string message = e.what();
    INFO(message);
    CHECK(message.find("gamma") != std::string::npos);
    CHECK(message.find("eta") != std::string::npos);
    CHECK(message.find("beta,") == std::string::npos);
  }
  // With gamma and eta fixed, rotation determines beta and delta.
  CDriveFitOptions options;
  options.free = {"beta", "delta"};
  auto start = Start();
  start.viscous_collar = 0.004333;
  start.coulomb_collar = 0.1501;
  const auto out = FitCDriveFriction(Programs(4.0, 2, 3, true), Given(start), options);
  CHECK(Estimate(out.fit, "beta") == Approx(0.002655).epsilon(0.03));
  CHECK(Estimate(out.fit, "delta") == Approx(0.1086).epsilon(0.03));
}

TEST_CASE("inertia: I_h and I_c within 5 % from fast programs with m fixed; a and b reported") {
  auto start = Start();
  start.viscous_motor = 0.002655;
  start.viscous_collar = 0.004333;
  start.coulomb_motor = 0.1086;
  start.coulomb_collar = 0.1501;
  start.hub_inertia = 6e-4 * 2.5;
  start.collar_inertia = 1.6e-3 / 3.0;
  CDriveFitOptions options;
  options.half_window = 0.005;
  const auto out = FitCDriveInertia(Programs(0.25, 3, 5), Given(start), options);
  CHECK(Estimate(out.fit, "I_h") == Approx(6e-4).epsilon(0.05));
  CHECK(Estimate(out.fit, "I_c") == Approx(1.6e-3).epsilon(0.05));
  REQUIRE(out.derived.size() == 2);
  const double k = 0.06 * 0.06 / (16 * M_PI * M_PI);
  CHECK(out.derived[0].value == Approx(6e-4 + 1.6e-3 / 4 + k * 2).epsilon(0.03));
  CHECK(out.derived[1].value == Approx(1.6e-3 / 4 - k * 2).epsilon(0.05));
  CHECK(out.derived[0].standard_error > 0.0);
  // All three free: refused, advising which to fix.
  options.free = {"I_h", "I_c", "m"};
  CHECK_THROWS_WITH(FitCDriveInertia(Programs(0.25, 3, 5), Given(start), options),
                    Catch::Contains("fix one of I_h, I_c, m"));
}

TEST_CASE("currents with k_t, and missing k_t refused") {
  const std::string text = "t,psi_L,psi_R,i_L,i_R\n0,0,0,1,2\n";
  const auto log = ParseCDriveLog("c.csv", text, {}, 0.5);
  CHECK(log.torque_left[0] == 0.5);
  CHECK(log.torque_right[0] == 1.0);
  CHECK_THROWS_WITH(ParseCDriveLog("c.csv", text, {}, std::nan("")), Catch::Contains("cdrive.k_t must be given"));
  CHECK_THROWS_AS(ParseCDriveLog("c.csv", "t,psi_L,psi_R,i_L,tau_R\n0,0,0,1,2\n", {}, 0.5), InputError);
}

TEST_CASE("friction without the inertias: a + b and a - b are estimated alongside") {
  CDriveSection start = Given(Start());
  start.hub_inertia = start.collar_inertia = start.collar_mass = std::nullopt;
  const auto out = FitCDriveFriction(Programs(4.0, 2, 21), start, {});
  CHECK(Estimate(out.fit, "beta") == Approx(0.002655).epsilon(0.03));
  CHECK(Estimate(out.fit, "gamma") == Approx(0.004333).epsilon(0.03));
  CHECK(Estimate(out.fit, "delta") == Approx(0.1086).epsilon(0.03));
  CHECK(Estimate(out.fit, "eta") == Approx(0.1501).epsilon(0.03));
  const double k = 0.06 * 0.06 / (16 * M_PI * M_PI);
  CHECK(Estimate(out.fit, "a_plus_b") == Approx(6e-4 + 1.6e-3 / 2).epsilon(0.05));
  CHECK(Estimate(out.fit, "a_minus_b") == Approx(6e-4 + 2 * k * 2.0).epsilon(0.05));
  REQUIRE(out.derived.size() == 2);
  CHECK(out.derived[0].name == "a");
}
