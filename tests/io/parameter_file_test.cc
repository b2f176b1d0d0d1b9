#include "io/parameter_file.h"

#include <catch2/catch.hpp>

#include "core/errors.h"

using namespace driveid;

namespace {
const char* kValid =
    "drivetrain:\n"
    "  n_g: 80\n"
    "  k_Tl: 15000.0\n"
    "  k_Tg: 18375\n"
    "  Theta_motor: 6.453e-5\n"
    "  Theta_g: 6.72e-6\n"
    "  d_g: 0.016\n"
    "  tau_c: 5.0\n";

std::string ErrorOf(const std::string& text) {
  try {
    ParseParameterFile("p.yaml", text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}
}  // namespace

TEST_CASE("reads the drivetrain section with units") {
  const auto file = ParseParameterFile("p.yaml", kValid);
  REQUIRE(file.drivetrain);
  CHECK(file.drivetrain->gear_ratio == 80.0);
  CHECK(file.drivetrain->motor_inertia == 6.453e-5);
  CHECK(file.drivetrain->coulomb_friction == 5.0);
}

TEST_CASE("formatted files read back unchanged, with a fit section too") {
  auto file = ParseParameterFile("p.yaml", kValid);
  file.drivetrain->viscous_friction = 0.015984787675731638;  // needs all 17 digits
  FitResult fit;
  fit.estimates.push_back({"d_g", 0.015984787675731638, 2e-5, 0.01594, 0.01602});
  fit.correlation = {1.0};
  fit.channels.push_back({"a \"quoted\" log.csv:tau_link", 201, 0.1, 99.5});
  fit.singular_values = {1.0};
  fit.converged = true;
  FitProvenance provenance{"drivetrain-fit step 'a b.csv'", "0.1.0", "reduced", {{"a b.csv", "00ff", 201}}};
  const std::string text = FormatParameterFile(file, &fit, &provenance);
  const auto again = ParseParameterFile("q.yaml", text);
  REQUIRE(again.drivetrain);
  CHECK(again.drivetrain->viscous_friction == file.drivetrain->viscous_friction);
  CHECK(again.drivetrain->link_stiffness == file.drivetrain->link_stiffness);
  CHECK(again.had_fit_section);
  CHECK(FormatParameterFile(again) == FormatParameterFile(file));
}

TEST_CASE("bad parameter files name file, line, column and key") {
  CHECK(ErrorOf(std::string(kValid) + "  k_TL: 3\n") ==
        "p.yaml:9:3: drivetrain.k_TL: unknown key (known: n_g, k_Tl, k_Tg, Theta_motor, Theta_g, d_g, tau_c)");
  CHECK_THAT(ErrorOf("drivetrain:\n  n_g: 80\n  k_Tl: -15000\n"),
             Catch::StartsWith("p.yaml:3:9: drivetrain.k_Tl: must be > 0, got -15000"));
  CHECK(ErrorOf("drivetrain:\n  n_g: 80\n  k_Tl: .nan\n") == "p.yaml:3:9: drivetrain.k_Tl: not a finite number: \".nan\"");
  CHECK(ErrorOf("drivetrain:\n  n_g: eighty\n") == "p.yaml:2:8: drivetrain.n_g: not a finite number: \"eighty\"");
  CHECK_THAT(ErrorOf("drivetrain:\n  n_g: 80\n"), Catch::Contains("drivetrain.k_Tl: missing value"));
  CHECK_THAT(ErrorOf("drivetrain: [1, 2\n"), Catch::StartsWith("p.yaml:"));
  CHECK_THAT(ErrorOf("drivetrain: [1, 2\n"), Catch::Contains("invalid YAML"));
  CHECK(ErrorOf("") == "p.yaml: empty parameter file");
  CHECK(ErrorOf("drivetrian:\n  n_g: 80\n") ==
        "p.yaml:1:1: drivetrian: unknown section (known: drivetrain, axis, planar_robot, cdrive, fit)");
  CHECK(ErrorOf("drivetrain:\n  n_g: 80\n  n_g: 81\n") == "p.yaml:3:3: drivetrain.n_g: key appears twice");
  CHECK(ErrorOf("- 1\n- 2\n") == "p.yaml:1:1: parameter file: expected a mapping of keys");
  CHECK_THAT(ErrorOf(std::string(kValid) + "  tau_c2: [1]\n"), Catch::Contains("unknown key"));
}
