// Axis IDIM-LS (docs/models.md#axis): recovery from synthetic logs, constant-rate logs
// identify friction only, the zero-phase filter has no lag.
#include "fit/axis_fit.h"

#include <cmath>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "signal/butterworth.h"
#include "sim/axis_experiment.h"

using namespace driveid;

namespace {
const AxisParameters kTruth{0.05, 0.2, 1.0, 0.3};
}

TEST_CASE("zero-phase Butterworth: unit DC gain, no lag, -6 dB at the cutoff") {
  std::vector<double> x(4000), slow(4000), fast(4000);
  for (int k = 0; k < 4000; ++k) {
    x[static_cast<std::size_t>(k)] = 2.0;
    slow[static_cast<std::size_t>(k)] = std::sin(2 * M_PI * 1.0 * k / 1000.0);
    fast[static_cast<std::size_t>(k)] = std::sin(2 * M_PI * 25.0 * k / 1000.0);
  }
  const auto dc = ZeroPhaseLowPass(x, 25.0, 1000.0);
  CHECK(dc[2000] == Approx(2.0));
  const auto s = ZeroPhaseLowPass(slow, 25.0, 1000.0);
  CHECK(s[2000 + 250] == Approx(slow[2000 + 250]).margin(1e-3));  // peak of the 1 Hz sine: no lag
  const auto f = ZeroPhaseLowPass(fast, 25.0, 1000.0);
  double peak = 0.0;
  for (int k = 1000; k < 3000; ++k) peak = std::max(peak, std::abs(f[static_cast<std::size_t>(k)]));
  CHECK(peak == Approx(0.5).epsilon(0.02));  // |H|^2 of a second-order Butterworth at the cutoff
  CHECK(ConstantRate({0, 0.001, 0.002, 0.003}) == Approx(1000.0));
  CHECK(ConstantRate({0, 0.001, 0.0025, 0.003}) == 0.0);
}

TEST_CASE("axis: multisine logs recover the truth within 1 % with the defaults") {
  for (unsigned seed : {1u, 2u, 3u}) {
    AxisExperiment e;
    e.noise = 0.05;
    e.duration = 25.0;
    e.seed = seed;
    const AxisFitOutput out = FitAxis({SimulateAxisExperiment(kTruth, e)}, AxisSection{0.1, 0.5, 2.0, 0.0, {}, {}, {}, {}}, {});
    CHECK(out.params.inertia == Approx(kTruth.inertia).epsilon(0.01));
    CHECK(out.params.viscous == Approx(kTruth.viscous).epsilon(0.01));
    CHECK(out.params.coulomb == Approx(kTruth.coulomb).epsilon(0.01));
    CHECK(out.params.offset == Approx(kTruth.offset).epsilon(0.01));
    CHECK(out.relative_error_percent < 3.0);
  }
}

TEST_CASE("axis: irregular sampling is detected and handled without assuming a rate") {
  AxisExperiment e;
  e.noise = 0.05;
  e.duration = 25.0;
  AxisLog log = SimulateAxisExperiment(kTruth, e);
  // Drop every 7th sample: the rate is no longer constant.
  AxisLog irregular{log.path, {}, {}, {}};
  for (std::size_t k = 0; k < log.time.size(); ++k) {
    if (k % 7 == 3) continue;
    irregular.time.push_back(log.time[k]);
    irregular.position.push_back(log.position[k]);
    irregular.force.push_back(log.force[k]);
  }
  const AxisFitOutput out = FitAxis({irregular}, AxisSection{0.1, 0.5, 2.0, 0.0, {}, {}, {}, {}}, {});
  CHECK(out.method.find("irregular") != std::string::npos);
  CHECK(out.params.inertia == Approx(kTruth.inertia).epsilon(0.02));
  CHECK(out.params.coulomb == Approx(kTruth.coulomb).epsilon(0.02));
}

TEST_CASE("axis: constant-rate logs identify friction only, a free inertia is refused by name") {
  std::vector<AxisLog> logs;
  for (double speed : {0.5, -0.5, 2.0, -2.0}) {
    AxisExperiment e;
    e.profile = "constant";
    e.speed = speed;
    e.noise = 0.05;
    e.duration = 5.0;
    logs.push_back(SimulateAxisExperiment(kTruth, e));
  }
  AxisSection start{std::nullopt, 0.5, 2.0, 0.0, {}, {}, {}, {}};  // inertia not given
  try {
    FitAxis(logs, start, {});
    FAIL("fitted an inertia from constant-rate logs");
  } catch (const IdentificationError& e) {
    CHECK(std::string(e.what()).find("inertia") != std::string::npos);
  }
  AxisFitOptions friction;
  friction.free = {"viscous", "coulomb", "offset"};
  const AxisFitOutput out = FitAxis(logs, start, friction);
  CHECK(out.params.viscous == Approx(kTruth.viscous).epsilon(0.01));
  CHECK(out.params.coulomb == Approx(kTruth.coulomb).epsilon(0.01));
  CHECK(out.params.offset == Approx(kTruth.offset).epsilon(0.01));
}
