// The test-only model of tests/support/test_spring_model.h, added by
// following docs/adding-a-model.md: its fit is a row builder for the shared
// LinearRegression; the parameter-file reader and writer, --free
// validation, bounds and start values all come from its table.
#include <cmath>
#include <map>
#include <random>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "fit/core/linear_regression.h"
#include "params/parameter_file.h"
#include "support/test_spring_model.h"

using namespace driveid;
using driveid::testing::SpringParameters;
using driveid::testing::SpringParameterTable;
using driveid::testing::SpringSection;

namespace {

struct SpringLog {
  std::vector<double> x, v, force;
};

// The fit: one row per sample, columns named by the table's keys.
FitResult FitSpring(const SpringLog& log, const SpringSection& start, const std::vector<std::string>& free) {
  CheckFreeNames(SpringParameterTable(), "spring", free);
  LinearRegression regression({"k", "c", "f0"});
  regression.BeginChannel("spring.csv:F");
  for (std::size_t i = 0; i < log.x.size(); ++i) regression.AddRow({log.x[i], log.v[i], 1.0}, log.force[i]);
  std::vector<FitParameter> parameters;
  std::map<std::string, double> fixed;
  for (const auto& row : SpringParameterTable()) {
    const double value = (start.*(row.in_section)).value_or(0.0);
    if (std::find(free.begin(), free.end(), row.spec.key) != free.end()) {
      parameters.push_back({row.spec.key, value, row.spec.lower_bound, 0.0});
    } else {
      fixed[row.spec.key] = value;
    }
  }
  return regression.Fit(parameters, fixed, {});
}

// An independent generator: a damped oscillation sampled at 1 kHz, the
// force from the equation written out here, Gaussian noise.
SpringLog Generate(double k, double c, double f0, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  SpringLog log;
  for (int i = 0; i < 2000; ++i) {
    const double t = i * 1e-3;
    const double x = 0.01 * std::exp(-t) * std::sin(2 * M_PI * 3.0 * t) + 0.002 * std::sin(2 * M_PI * 0.7 * t);
    const double v = 0.01 * std::exp(-t) * (2 * M_PI * 3.0 * std::cos(2 * M_PI * 3.0 * t) - std::sin(2 * M_PI * 3.0 * t)) +
                     0.002 * 2 * M_PI * 0.7 * std::cos(2 * M_PI * 0.7 * t);
    log.x.push_back(x);
    log.v.push_back(v);
    log.force.push_back(k * x + c * v + f0 + noise(rng));
  }
  return log;
}

}  // namespace

TEST_CASE("a test-only model added by following docs/adding-a-model.md: file section, --free, fit, write back") {
  REQUIRE(driveid::testing::kSpringSectionRegistered);
  // The parameter file reads the section from the table: values, bounds, unknown keys.
  const ParameterFile file = ParseParameterFile("s.yaml", "test_spring:\n  k: 1000\n  c: 2\n  f0: 0\n");
  REQUIRE(file.Find<SpringSection>() != nullptr);
  CHECK(*file.Find<SpringSection>()->stiffness == 1000.0);
  CHECK_THROWS_WITH(ParseParameterFile("s.yaml", "test_spring:\n  k: -1\n"),
                    Catch::StartsWith("s.yaml:2:6: test_spring.k: must be >= 0"));
  CHECK_THROWS_WITH(ParseParameterFile("s.yaml", "test_spring:\n  q: 1\n"),
                    Catch::StartsWith("s.yaml:2:3: test_spring.q: unknown key (known: k, c, f0)"));
  // --free names come from the table.
  CHECK(FitParameterKeys(SpringParameterTable(), "spring", true) == std::vector<std::string>{"k", "c", "f0"});
  CHECK_THROWS_AS(FitSpring({}, {}, {"k", "mass"}), OptionError);

  // The fit recovers the generator's values within their intervals.
  const SpringLog log = Generate(2500.0, 4.0, 1.5, 0.05, 7);
  const FitResult fit = FitSpring(log, *file.Find<SpringSection>(), {"k", "c", "f0"});
  const std::map<std::string, double> truth = {{"k", 2500.0}, {"c", 4.0}, {"f0", 1.5}};
  for (const auto& e : fit.estimates) {
    INFO(e.name << " = " << e.value << " +- " << e.standard_error);
    CHECK(std::abs(e.value - truth.at(e.name)) <= 4.0 * e.standard_error);
  }

  // Estimates go back into the section and the written file reads back.
  SpringParameters fitted;
  fitted.stiffness = fit.estimates[0].value;
  fitted.damping = fit.estimates[1].value;
  fitted.preload = fit.estimates[2].value;
  ParameterFile out = file;
  StoreModelParameters(SpringParameterTable(), fitted, *out.Find<SpringSection>());
  const std::string text = FormatParameterFile(out, &fit);
  CHECK(text.find("test_spring:") != std::string::npos);
  CHECK(text.find("# spring stiffness [N/m]") != std::string::npos);
  const ParameterFile again = ParseParameterFile("again.yaml", text);
  REQUIRE(again.Find<SpringSection>() != nullptr);
  CHECK(*again.Find<SpringSection>()->stiffness == fitted.stiffness);
  CHECK(driveid::testing::SpringForce(fitted, 0.001, 0.0) == Approx(2.5 + 1.5).margin(0.1));
}
