// The fit core: a model that cannot be evaluated is reported with its
// reason and the parameter values, so the user sees why (e.g. CVODES's
// message), not only that it failed.
#include "fit/least_squares.h"

#include <cmath>
#include <string>

#include <catch2/catch.hpp>

#include "core/errors.h"

using namespace driveid;

namespace {
class FailingModel final : public ResidualModel {
 public:
  int residual_count() const override { return 10; }
  bool Evaluate(const double*, double*, double*) override { return false; }
  std::string LastFailure() const override { return "integrator: CVode failed with code -4 (convergence test failures)"; }
};
}  // namespace

TEST_CASE("a model that cannot be evaluated: the reason and the parameter values reach the message") {
  FailingModel model;
  const std::vector<FitParameter> parameters = {{"d_g", 0.016, 0.0, 0.0}, {"tau_c", 5.0, 0.0, 0.0}};
  try {
    FitLeastSquares(model, parameters, {{"y", 0, 10, nullptr}}, {});
    FAIL("fitted a model that cannot be evaluated");
  } catch (const IdentificationError& e) {
    const std::string message = e.what();
    INFO(message);
    CHECK(message.find("d_g = 0.016") != std::string::npos);
    CHECK(message.find("tau_c = 5") != std::string::npos);
    CHECK(message.find("convergence test failures") != std::string::npos);
  }
}

TEST_CASE("Student t 97.5 % quantiles: exact values at small and large degrees of freedom") {
  // Reference values of the t distribution (two-sided 95 %).
  CHECK(StudentT975(1) == Approx(12.7062047362).epsilon(1e-9));
  CHECK(StudentT975(2) == Approx(4.30265272975).epsilon(1e-9));
  CHECK(StudentT975(10) == Approx(2.22813885196).epsilon(1e-9));
  CHECK(StudentT975(30) == Approx(2.04227245630).epsilon(1e-9));
  CHECK(StudentT975(100) == Approx(1.98397151852).epsilon(1e-9));
  CHECK(StudentT975(100000) == Approx(1.9599877).epsilon(1e-7));  // z + (z^3 + z) / (4 n)
  CHECK(std::isinf(StudentT975(0)));
}
