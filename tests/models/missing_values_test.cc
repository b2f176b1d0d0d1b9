// models/missing_values.h: every missing model value named at once, with
// the line to add; terms that are 0 unless given are not asked for.
#include "models/missing_values.h"

#include <catch2/catch.hpp>

#include "models/axis.h"
#include "models/joint.h"

using namespace driveid;

TEST_CASE("missing values: all named in one message, with the lines to add") {
  JointSection joint;
  joint.motor_inertia = 0.02;
  joint.stiffness = 20.0;
  const auto missing = MissingModelValues(JointParameterTable(), joint);
  std::vector<std::string> keys;
  for (const ParameterSpec* spec : missing) keys.emplace_back(spec->key);
  CHECK(std::find(keys.begin(), keys.end(), "link_inertia") != keys.end());
  CHECK(std::find(keys.begin(), keys.end(), "damping") != keys.end());
  CHECK(std::find(keys.begin(), keys.end(), "motor_inertia") == keys.end());
  CHECK(std::find(keys.begin(), keys.end(), "stiffness") == keys.end());
  try {
    RequireModelValues(JointParameterTable(), joint, "j.yaml", "joint", "the simulation");
    FAIL("no refusal");
  } catch (const InputError& e) {
    const std::string message = e.what();
    CHECK(message.rfind("j.yaml: ", 0) == 0);
    CHECK(message.find("joint.link_inertia") != std::string::npos);
    CHECK(message.find("joint.damping") != std::string::npos);
    CHECK(message.find("'link_inertia: <value>'") != std::string::npos);
    CHECK(message.find("the simulation") != std::string::npos);
  }
  // An axis without gravity: gravity is 0 unless given, so only J, b, tau_c, tau_0 are asked for.
  AxisSection axis;
  axis.inertia = 0.05;
  axis.viscous = 0.2;
  axis.coulomb = 1.0;
  axis.offset = 0.3;
  CHECK(MissingModelValues(AxisParameterTable(), axis, AxisTermsZeroUnlessGiven(axis)).empty());
  CHECK_NOTHROW(RequireModelValues(AxisParameterTable(), axis, "a.yaml", "axis", "x", AxisTermsZeroUnlessGiven(axis)));
}
