// Where a WPILog holds SysId data (logs/formats/wpilog_routines.h): SysId's
// state names in every spelling the loggers write, the tests found from a
// voltage written here (ramps from rest, held steps, an aborted run, a
// pause in the records), and the position's unit from an entry's metadata or
// an AdvantageKit name.
#include "logs/formats/wpilog_routines.h"

#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

using namespace driveid;

TEST_CASE("wpilog routines: SysId's state names in every spelling") {
  CHECK(CanonicalSysIdState("quasistatic-forward") == "quasistatic-forward");
  CHECK(CanonicalSysIdState("kQuasistaticReverse") == "quasistatic-reverse");
  CHECK(CanonicalSysIdState("State.kDynamicForward") == "dynamic-forward");
  CHECK(CanonicalSysIdState("SysIdRoutineLog.State.kDynamicReverse") == "dynamic-reverse");
  CHECK(CanonicalSysIdState("kNone") == "none");
  CHECK(CanonicalSysIdState("none") == "none");
  CHECK(CanonicalSysIdState("").empty());
  CHECK(CanonicalSysIdState("kick").empty());
  CHECK(CanonicalSysIdState("dynamic").empty());
}

namespace {

// Appends `seconds` of records at 50 Hz from `t` [s] of a voltage given by `v(elapsed)`.
void Append(std::vector<double>& t_us, std::vector<double>& volts, double& t, double seconds, double (*v)(double)) {
  for (double e = 0.0; e < seconds - 1e-9; e += 0.02) {
    t_us.push_back(std::round((t + e) * 1e6));
    volts.push_back(v(e));
  }
  t += seconds;
}

}  // namespace

TEST_CASE("wpilog routines: the tests from the voltage alone") {
  std::vector<double> t_us, volts;
  double t = 1.0;
  Append(t_us, volts, t, 1.0, [](double e) { return 1.0 * e; });  // aborted quasistatic-forward
  Append(t_us, volts, t, 0.5, [](double) { return 0.0; });        // at rest, logged
  Append(t_us, volts, t, 5.0, [](double e) { return 1.0 * e; });  // quasistatic-forward
  t += 2.0;                                                        // a pause in the records
  Append(t_us, volts, t, 5.0, [](double e) { return -1.0 * e; }); // quasistatic-reverse
  t += 1.0;
  Append(t_us, volts, t, 2.0, [](double) { return 7.0; });        // dynamic-forward
  Append(t_us, volts, t, 2.0, [](double) { return -7.0; });       // dynamic-reverse, no rest between
  std::vector<std::string> notes;
  const auto states = StatesFromVoltage(t_us, volts, notes);
  std::vector<std::string> tests;
  for (const auto& [at, state] : states) {
    if (state != "none") tests.push_back(state);
  }
  CHECK(tests == std::vector<std::string>{"quasistatic-forward", "quasistatic-forward", "quasistatic-reverse",
                                          "dynamic-forward", "dynamic-reverse"});
  REQUIRE(states.size() == 10);
  // Each test from its first record above rest to the next record after it.
  CHECK(states[2].first > 2.5e6);  // the second ramp's first record above rest (2 % of 7 V)
  CHECK(states[2].first < 2.7e6);
  CHECK(states[3].first == static_cast<std::int64_t>(std::round(9.5 * 1e6)));   // the next test's first record
  for (std::size_t k = 1; k < states.size(); ++k) CHECK(states[k].first >= states[k - 1].first);
  REQUIRE(notes.size() == 1);
  CHECK(notes[0].find("tests found from the voltage pattern") != std::string::npos);
  // A voltage that neither ramps nor holds makes no test, and says so.
  std::vector<double> t2, v2;
  double t0 = 0.0;
  Append(t2, v2, t0, 4.0, [](double e) { return 6.0 + 4.0 * std::sin(6.0 * e); });
  notes.clear();
  CHECK(StatesFromVoltage(t2, v2, notes).empty());
  REQUIRE(notes.size() == 1);
  CHECK(notes[0].find("none found") != std::string::npos);
  CHECK(StatesFromVoltage({}, {}, notes).empty());
  CHECK(StatesFromVoltage({0.0, 1.0, 2.0}, {0.0, 0.0, 0.0}, notes).empty());
}

TEST_CASE("wpilog routines: the position's unit") {
  CHECK(WpilogPositionUnit("Meter", "position-a-b") == "Meters");
  CHECK(WpilogPositionUnit("Rotation", "") == "Rotations");
  CHECK(WpilogPositionUnit("Furlong", "x") == "Furlong");
  CHECK(WpilogPositionUnit("", "/Drive/Module0/DrivePositionRad") == "Radians");
  CHECK(WpilogPositionUnit("", "/Arm/PositionRotations") == "Rotations");
  CHECK(WpilogPositionUnit("", "/Elevator/positionMeters") == "Meters");
  CHECK(WpilogPositionUnit("", "/drive/leftPosition").empty());
  CHECK(WpilogPositionUnit("{\"source\":\"NT\"}", "/drive/leftPosition").empty());
}
