// core/fit_section.h: the fit section's keys declared once. The parameter
// file writes every key in the declared order (model and derived when
// there are any), reads back what it wrote, refuses a key it does not
// declare by listing the declared ones, and the JSON summary carries the
// same keys (derived only in the file).
#include "core/fit_section.h"

#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "params/parameter_file.h"
#include "report/fit_summary.h"

using namespace driveid;

namespace {

FitResult SmallFit() {
  FitResult fit;
  fit.estimates = {{"inertia", 0.05, 0.001, 0.048, 0.052, "kg m^2"}, {"viscous", 0.2, 0.01, 0.18, 0.22, ""}};
  fit.correlation = {1.0, 0.3, 0.3, 1.0};
  fit.covariance = {1e-6, 3e-6, 3e-6, 1e-4};
  ChannelStatistics c;
  c.name = "a.csv:tau";
  c.samples = 100;
  c.rmse = 0.01;
  c.fit_percent = 95.0;
  fit.channels = {c};
  fit.singular_values = {1.2, 0.8};
  fit.iterations = 4;
  fit.converged = true;
  return fit;
}

// The top-level keys under "fit:" in the written text, in order.
std::vector<std::string> WrittenFitKeys(const std::string& text) {
  std::vector<std::string> keys;
  const std::size_t fit = text.find("\nfit:\n");
  REQUIRE(fit != std::string::npos);
  for (std::size_t at = fit + 6; at < text.size();) {
    const std::size_t end = text.find('\n', at);
    const std::string line = text.substr(at, end - at);
    at = end == std::string::npos ? text.size() : end + 1;
    if (line.size() > 2 && line[0] == ' ' && line[1] == ' ' && line[2] != ' ' && line[2] != '-' && line[2] != '#') {
      keys.push_back(line.substr(2, line.find(':') - 2));
    }
  }
  return keys;
}

}  // namespace

TEST_CASE("fit section: written in the declared order, read back, other keys refused, the JSON alike") {
  const FitResult fit = SmallFit();
  FitProvenance provenance{"drivetrain-fit axis a.csv", "0.1.0", "axis", {{"a.csv", "ab12", 100, "", {}}}};
  const std::vector<DerivedQuantity> derived = {{"a", 1.0, 0.1, "kg"}};
  AxisSection axis;
  axis.inertia = 0.05;
  ParameterFile file;
  file.Set(axis);
  const std::string text = FormatParameterFile(file, &fit, &provenance, derived);
  std::vector<std::string> declared;
  for (const FitKey key : kFitSectionKeys) declared.emplace_back(FitKeyName(key));
  CHECK(WrittenFitKeys(text) == declared);

  const ParameterFile read = ParseParameterFile("p.yaml", text);
  CHECK(read.had_fit_section);
  REQUIRE(read.fit_estimates.size() == 2);
  CHECK(read.fit_estimates[1].standard_error == Approx(0.01));

  // Without a model and derived quantities those two keys are left out.
  provenance.model.clear();
  std::vector<std::string> without = declared;
  without.erase(std::find(without.begin(), without.end(), "derived"));
  without.erase(std::find(without.begin(), without.end(), "model"));
  CHECK(WrittenFitKeys(FormatParameterFile(file, &fit, &provenance, {})) == without);

  std::string unknown = text;
  unknown.replace(unknown.find("  converged:"), 12, "  convergent:");
  CHECK_THROWS_AS(ParseParameterFile("p.yaml", unknown), InputError);
  CHECK_THROWS_WITH(ParseParameterFile("p.yaml", unknown),
                    Catch::Contains("fit.convergent: unknown key") &&
                        Catch::Contains("known: command, version, model, data, estimates, derived, correlation"));

  const Json json = FitJson(fit, provenance);
  for (const FitKey key : kFitSectionKeys) {
    INFO(FitKeyName(key));
    CHECK(json.contains(FitKeyName(key)) == (key != FitKey::kDerived));
  }
}

TEST_CASE("a negative standard error or an inverted interval is refused where it is written (issue 55)") {
  const std::string axis = "axis:\n  inertia: 0.05\n";
  const std::string negative =
      axis + "fit:\n  estimates:\n    inertia: {value: 0.05, std: -0.001, ci95: [0.049, 0.051]}\n";
  CHECK_THROWS_WITH(ParseParameterFile("p.yaml", negative),
                    Catch::Contains("p.yaml:5") && Catch::Contains("fit.estimates.inertia.std = -0.001: a standard error is >= 0"));
  const std::string inverted = axis + "fit:\n  estimates:\n    inertia: {value: 0.05, std: 0.001, ci95: [0.051, 0.049]}\n";
  CHECK_THROWS_WITH(ParseParameterFile("p.yaml", inverted),
                    Catch::Contains("fit.estimates.inertia.ci95 = [0.051, 0.049]: the low end lies above the high end"));
  const std::string gain = axis +
                           "feedforward:\n  law: axis\n  effort_unit: \"V\"\n  position_unit: \"rad\"\n"
                           "  Kv: {value: 0.12, std: -0.002}\n";
  CHECK_THROWS_WITH(ParseParameterFile("p.yaml", gain), Catch::Contains("feedforward.Kv.std = -0.002: a standard error is >= 0"));
  // Zero is a standard error (a value held fixed).
  const std::string zero = axis + "fit:\n  estimates:\n    inertia: {value: 0.05, std: 0, ci95: [0.05, 0.05]}\n";
  CHECK(ParseParameterFile("p.yaml", zero).fit_estimates.at(0).standard_error == 0.0);
}
