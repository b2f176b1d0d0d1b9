// The joint design's excitation and panels (report/joint_design_report.h):
// the designed multisine on the logging grid repeats with its period, holds
// each line at its amplitude (the DFT over one period, computed here) and
// nothing between the lines, and has the rms sqrt(sum A^2 / 2).
#include <cmath>

#include <catch2/catch.hpp>

#include "report/joint_design_report.h"
#include "support/dft_bin.h"

namespace driveid {
namespace {

TEST_CASE("the designed multisine: periodic, its lines at their amplitudes and nothing between, its rms") {
  JointDesign d;
  d.period = 2.0;
  d.frequency = {1.0, 2.5, 7.0};
  d.designed.name = "designed";
  d.designed.amplitude = {0.3, 0.1, 0.05};
  d.designed.phase = {0.2, -1.0, 2.5};
  d.naive.name = "default multisine";
  d.naive.amplitude = {0.1, 0.1, 0.1};
  d.naive.phase = {0.0, 0.0, 0.0};
  const double rate = 500.0;
  const TorqueReference r = DesignedExcitation(d, rate, 4.0);
  const std::size_t n = 1000;  // one period
  REQUIRE(r.torque.size() == 2 * n);
  double power = 0.0, repeat = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    CHECK(r.time[k] == Approx(static_cast<double>(k) / rate));
    power += r.torque[k] * r.torque[k];
    repeat = std::max(repeat, std::abs(r.torque[k + n] - r.torque[k]));
  }
  CHECK(repeat < 1e-12);
  CHECK(std::sqrt(power / n) == Approx(std::sqrt((0.09 + 0.01 + 0.0025) / 2.0)).epsilon(1e-12));
  double between = 0.0;
  for (int bin = 1; bin < 40; ++bin) {
    const double amplitude = testing::LineAmplitude(r.torque, n, bin);
    const double f = bin / d.period;
    bool line = false;
    for (std::size_t j = 0; j < d.frequency.size(); ++j) {
      if (std::abs(f - d.frequency[j]) < 1e-9) {
        CHECK(amplitude == Approx(d.designed.amplitude[j]).epsilon(1e-9));
        line = true;
      }
    }
    if (!line) between = std::max(between, amplitude);
  }
  CHECK(between < 1e-12);
  const std::vector<PlotPanel> panels = JointDesignPanels(d, rate);
  REQUIRE(panels.size() == 2);
  CHECK(panels[1].lines[0].x == d.frequency);
  CHECK(panels[1].lines[0].y == d.designed.amplitude);
  CHECK(panels[0].lines[1].y.size() == n);
}

}  // namespace
}  // namespace driveid
