// What the two-mass model lacks, named (fit/joint/joint_mismatch.h): logs from the
// independent closed-loop friction-joint generator
// (tests/support/reference_joint_friction.cc) with gear backlash, a
// hardening spring or torque ripple at the 6th order of the motor's
// rotation, fitted by the inverse-dynamics joint fit with its defaults;
// the plain joint draws neither warning.
#include <string>

#include <catch2/catch.hpp>

#include "fit/joint/joint_fit.h"
#include "support/friction_joint_cases.h"

using namespace driveid;
using namespace driveid::testing;

namespace {

std::string Warned(const JointFitOutput& fit, const std::string& what) {
  for (const auto& w : fit.fit.warnings) {
    if (w.find(what) != std::string::npos) return w;
  }
  return "";
}

JointFitOutput Fit(const FrictionJointTruth& truth, std::uint64_t seed) {
  FrictionJointExperiment e;
  e.seed = seed;
  e.torque_noise = 0.005;
  e.torque_noise_ar = 0.5;
  JointSection start = FarJointStart(truth);
  JointFitOptions options;
  options.refuse_undetermined = false;
  return FitJoint({ToJointLog(SimulateFrictionJoint(truth, e), "joint.csv")}, start, options);
}

}  // namespace

TEST_CASE("the plain two-mass joint draws no mismatch warning") {
  for (std::uint64_t seed : {1, 2, 3}) {
    const JointFitOutput fit = Fit(FrictionJointTruth{}, seed);
    INFO("seed " << seed);
    CHECK(Warned(fit, "depends on the deflection's amplitude").empty());
    CHECK(Warned(fit, "of the motor's rotation").empty());
  }
}

TEST_CASE("gear backlash and a hardening spring are named as an amplitude-dependent stiffness") {
  FrictionJointTruth backlash;
  backlash.backlash = 0.4e-3;
  const std::string b = Warned(Fit(backlash, 1), "depends on the deflection's amplitude");
  INFO(b);
  CHECK_THAT(b, Catch::Contains("softer at small deflections"));
  FrictionJointTruth hard;
  hard.hardening = 5e7;  // +10 % at 2 mrad
  const std::string h = Warned(Fit(hard, 1), "depends on the deflection's amplitude");
  INFO(h);
  CHECK_THAT(h, Catch::Contains("hardening spring"));
}

TEST_CASE("torque ripple at the 6th order of the motor's rotation is named with its order") {
  FrictionJointTruth ripple;
  ripple.ripple = 0.03;
  const std::string r = Warned(Fit(ripple, 1), "of the motor's rotation");
  INFO(r);
  CHECK_THAT(r, Catch::Contains("order 6 "));
}
