// The speed loop's notch as the workflow sizes it from the parameter file
// (workflow/feedback_design.h, docs/models.md#speed-loop): centred on the
// joint's resonance, as wide as 30 % of it or as the resonance's 95 %
// interval read from the frf section (2 x 1.96 x resonance_hz_std),
// whichever is wider; a width given overrides both. Each branch is reached
// here, so a std read wrong (scaled, or not read) fails.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "params/parameter_file.h"
#include "workflow/feedback_design.h"

using namespace driveid;

namespace {

const char* kJoint =
    "joint:\n  gear_ratio: 50\n  motor_inertia: 0.02\n  link_inertia: 0.05\n  stiffness: 20\n  damping: 0.05\n"
    "  motor_viscous: 0.1\n  motor_coulomb: 0.2\n  link_viscous: 0.05\n  link_coulomb: 0.1\n  offset: 0.05\n";

double Value(const JointGainsDesign& d, const std::string& key) {
  const FeedbackValue* v = d.controller.Find(key);
  REQUIRE(v != nullptr);
  return v->value;
}

// The two-mass resonance written apart from models/joint.h: the two
// inertias (both on the link side, as the joint section states them) on the
// spring k, omega^2 = k (J_m + J_l) / (J_m J_l).
double ResonanceHz() {
  const double jm = 0.02, jl = 0.05, k = 20.0;
  return std::sqrt(k * (jm + jl) / (jm * jl)) / (2.0 * M_PI);
}

JointGainsDesign Design(const std::string& frf, double width = 0.0) {
  const ParameterFile file = ParseParameterFile("joint.yaml", std::string(kJoint) + frf);
  JointGainsOptions o;
  o.notch_width_hz = width;
  return DesignJointGains(file, "joint.yaml", o);
}

}  // namespace

TEST_CASE("speed loop notch: 30 % of the resonance when its std is small") {
  const JointGainsDesign d = Design("frf:\n  resonance_hz: 3.2\n  resonance_hz_std: 0.01\n");
  CHECK(Value(d, "notch_hz") == Approx(ResonanceHz()).epsilon(1e-6));
  CHECK(Value(d, "notch_width_hz") == Approx(0.3 * ResonanceHz()).epsilon(1e-9));
}

TEST_CASE("speed loop notch: the resonance's 95 % interval when it is wider") {
  const double std_hz = 0.15 * ResonanceHz();  // 2 x 1.96 x 0.15 = 0.59 of the resonance
  const JointGainsDesign d = Design("frf:\n  resonance_hz: 3.2\n  resonance_hz_std: " + std::to_string(std_hz) + "\n");
  CHECK(Value(d, "notch_width_hz") == Approx(2.0 * 1.96 * std::stod(std::to_string(std_hz))).epsilon(1e-9));
}

TEST_CASE("speed loop notch: a width given overrides the data") {
  const JointGainsDesign d = Design("frf:\n  resonance_hz: 3.2\n  resonance_hz_std: 1.0\n", 0.5);
  CHECK(Value(d, "notch_width_hz") == 0.5);
}
