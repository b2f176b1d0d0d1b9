// The design's reference and panels (report/design_report.h): the reference
// on the logging grid is the designed Fourier series and its derivatives;
// the prior's torque is the axis model's inverse dynamics; each line's
// acceleration amplitude equals the sampled acceleration's DFT amplitude at
// that line (computed here).
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "design/fourier_reference.h"
#include "report/design_report.h"
#include "support/dft_bin.h"

namespace driveid {
namespace {

AxisDesign HandMade() {
  AxisDesign d;
  d.period = 10.0;
  d.designed.name = "designed";
  d.designed.reference = MakeRestingReference(0.1, {1, 3, 7, 12}, {0.3, -0.2, 0.05, 0.4, 0.1, -0.07});
  d.naive.name = "four sines";
  d.naive.reference = MakeRestingReference(0.1, {1, 4, 9, 16}, {0.1, 0.1, 0.1, 0.0, 0.0, 0.0});
  return d;
}

TEST_CASE("the designed reference on the logging grid, the prior's torque, and each line's acceleration amplitude") {
  const AxisDesign design = HandMade();
  AxisParameters prior;
  prior.inertia = 0.05;
  prior.viscous = 0.2;
  prior.coulomb = 1.0;
  prior.offset = 0.3;
  const double rate = 200.0;
  const AxisReference reference = DesignedReference(design, prior, rate, 20.0);
  REQUIRE(reference.time.size() >= 4000);
  double worst = 0.0;
  for (std::size_t k = 0; k < reference.time.size(); ++k) {
    const ReferenceSample3 s = design.designed.reference.At(reference.time[k]);
    CHECK(reference.time[k] == Approx(static_cast<double>(k) / rate));
    worst = std::max({worst, std::abs(reference.position[k] - s.position), std::abs(reference.rate[k] - s.rate),
                      std::abs(reference.acceleration[k] - s.acceleration)});
  }
  CHECK(worst < 1e-12);

  const std::vector<PlotPanel> panels = AxisDesignPanels(design, prior, rate);
  REQUIRE(panels.size() == 3);
  for (std::size_t c = 0; c < 2; ++c) {
    const AxisDesignCandidate& candidate = c == 0 ? design.designed : design.naive;
    const PlotLine& torque = panels[1].lines[c];
    const PlotLine& lines = panels[2].lines[c];
    INFO(candidate.name);
    // tau = J q'' + b q' + tau_c sgn(q') + tau_0 (no gravity, no Stribeck).
    double torque_error = 0.0;
    for (std::size_t k = 0; k < torque.x.size(); ++k) {
      const ReferenceSample3 s = candidate.reference.At(torque.x[k]);
      const double sign = s.rate > 0.0 ? 1.0 : s.rate < 0.0 ? -1.0 : 0.0;
      const double model = prior.inertia * s.acceleration + prior.viscous * s.rate + prior.coulomb * sign + prior.offset;
      torque_error = std::max(torque_error, std::abs(torque.y[k] - model));
    }
    CHECK(torque_error < 1e-9);
    // One period (10 s, 2000 samples): line n at bin n.
    const std::size_t n = 2000;
    std::vector<double> acceleration(n);
    for (std::size_t k = 0; k < n; ++k) acceleration[k] = candidate.reference.At(static_cast<double>(k) / rate).acceleration;
    REQUIRE(lines.x.size() == candidate.reference.harmonics.size());
    for (std::size_t j = 0; j < lines.x.size(); ++j) {
      const int harmonic = candidate.reference.harmonics[j];
      CHECK(lines.x[j] == Approx(0.1 * harmonic));
      CHECK(lines.y[j] == Approx(testing::LineAmplitude(acceleration, n, harmonic)).epsilon(1e-9));
    }
  }
}

}  // namespace
}  // namespace driveid
