// A servo drive's 4 kHz scope trace of an elastic axis
// (tests/support/reference_scope_trace.h: cascade control, point-to-point
// moves, raw counts, torque in per mille of rated with noise), read as a
// user reads it — column expressions only, the motor inertia from its data
// sheet as the only value beside the gear — and identified as `drivetrain-fit
// joint` does by default: the stiffness within 5 % with the truth inside
// its interval; the damping's interval holds the truth or a warning names
// the damping.
#include <cmath>
#include <string>

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include "logs/csv_log.h"
#include "logs/log_input.h"
#include "support/reference_scope_trace.h"
#include "workflow/joint_identification.h"

using namespace driveid;

TEST_CASE("a 4 kHz scope trace read with column expressions: stiffness within 5 % and inside its interval") {
  const driveid::testing::ScopeAxis axis;
  driveid::testing::ScopeSettings settings;
  const std::string text = driveid::testing::SimulateScopeTrace(axis, settings);
  LogInputOptions input;
  input.columns = {{"t", "time_ms/1000"},
                   {"q_motor", "pi/65536*enc_motor"},
                   {"q_link", "pi/524288*enc_link"},
                   {"tau", "0.01*torque_permille"}};
  auto csv = ReadLogs("scope.csv", text, {}, JointLogColumns(), input);
  REQUIRE(csv.size() == 1);
  const JointLog log = MakeJointLog(std::move(csv.front()), 0.0);
  JointSection section;
  section.gear_ratio = axis.gear_ratio;
  section.motor_inertia = axis.motor_inertia;  // the data sheet's
  const JointIdentification run = IdentifyJoint({log}, section, {});
  std::string shown;
  for (const auto& line : run.summary) shown += line + "\n";
  for (const auto& w : run.fit.warnings) shown += "warning: " + w + "\n";
  for (const auto& e : run.fit.estimates) shown += fmt::format("{} {} [{}, {}]\n", e.name, e.value, e.ci95_low, e.ci95_high);
  INFO(shown);
  const auto find = [&](const std::string& name) {
    for (const auto& e : run.fit.estimates) {
      if (e.name == name) return e;
    }
    FAIL("no estimate of " << name);
    return ParameterEstimate{};
  };
  const ParameterEstimate k = find("stiffness");
  CHECK(std::abs(k.value / axis.stiffness - 1.0) < 0.05);
  CHECK(k.ci95_low <= axis.stiffness);
  CHECK(axis.stiffness <= k.ci95_high);
  const ParameterEstimate d = find("damping");
  bool damping_warned = false;
  for (const auto& w : run.fit.warnings) damping_warned = damping_warned || w.find("damping") != std::string::npos;
  CHECK(((d.ci95_low <= axis.damping && axis.damping <= d.ci95_high) || damping_warned));
}
