// The excitation design (design/axis_excitation.h): the reference starts at
// rest and its derivatives are its own; the optimiser finds a known
// minimum; the designed reference keeps every limit on a finer grid than
// the design's; the predicted covariance is the inverse information computed
// here by quadrature over the whole log; the design beats four equal sines.
#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "design/axis_excitation.h"
#include "design/fourier_reference.h"
#include "design/nelder_mead.h"
#include "fit/axis/axis_rows.h"

using namespace driveid;

TEST_CASE("a resting reference starts at rest and differentiates to its own rate and acceleration") {
  const FourierReference r = MakeRestingReference(0.1, {1, 3, 7, 12}, {0.3, -0.2, 0.05, 0.4, 0.1, -0.07});
  const ReferenceSample3 s0 = r.At(0.0);
  CHECK(std::abs(s0.position) < 1e-12);
  CHECK(std::abs(s0.rate) < 1e-12);
  CHECK(std::abs(s0.acceleration) < 1e-12);
  const double h = 1e-5;
  for (double t : {0.37, 2.1, 7.9}) {
    const ReferenceSample3 s = r.At(t), a = r.At(t - h), b = r.At(t + h);
    CHECK(s.rate == Approx((b.position - a.position) / (2 * h)).epsilon(1e-6).margin(1e-8));
    CHECK(s.acceleration == Approx((b.rate - a.rate) / (2 * h)).epsilon(1e-6).margin(1e-8));
  }
  // Periodic: the same after one period.
  CHECK(r.At(3.3).position == Approx(r.At(13.3).position).margin(1e-9));
}

TEST_CASE("Nelder-Mead finds the minimum of Rosenbrock's function") {
  auto rosenbrock = [](const std::vector<double>& x) {
    return 100.0 * std::pow(x[1] - x[0] * x[0], 2) + std::pow(1.0 - x[0], 2);
  };
  const SimplexResult r = MinimiseNelderMead(rosenbrock, {-1.2, 1.0}, {0.5, 0.5}, 1e-14, 5000);
  CHECK(r.x[0] == Approx(1.0).margin(1e-4));
  CHECK(r.x[1] == Approx(1.0).margin(1e-4));
}

TEST_CASE("the designed reference keeps the limits, and its predicted covariance is the inverse information") {
  AxisParameters prior;
  prior.inertia = 0.05;
  prior.viscous = 0.2;
  prior.coulomb = 1.0;
  prior.offset = 0.3;
  AxisDesignOptions o;
  o.duration = 20.0;
  o.rate = 1000.0;
  o.max_position = 1.0;
  o.max_rate = 2.0;
  o.max_torque = 3.0;
  o.noise = 0.05;
  o.evaluations = 800;
  const AxisDesign d = DesignAxisExcitation(prior, o);
  REQUIRE(d.free.size() == 4);
  // Limits on a 10 kHz grid, the torque computed here.
  const int n = 200000;
  std::vector<ReferenceSample3> samples;
  std::vector<char> slow(n, 0);
  for (int k = 0; k < n; ++k) {
    samples.push_back(d.designed.reference.At(k * 1e-4));
    slow[static_cast<std::size_t>(k)] = std::abs(samples.back().rate) < 0.01 * d.designed.peaks.rate;
  }
  // The fit leaves out 4 decimations (40 ms at 1 kHz) on each side of a
  // slow sample at the band cutoff a designed log's fit takes
  // (fit/axis/axis_rows.h AxisExclusionReach); the reference repeats over the 20 s.
  for (const double rate : {500.0, 1000.0, 4000.0}) {
    CHECK(kDesignExclusionDecimations * 10 == AxisExclusionReach(rate, AxisDecimatedBand(rate, 10), 10));
  }
  std::vector<char> left_out(n, 0);
  for (int k = 0; k < n; ++k) {
    if (!slow[static_cast<std::size_t>(k)]) continue;
    for (int j = -400; j <= 400; ++j) left_out[static_cast<std::size_t>((k + j + n) % n)] = 1;
  }
  Eigen::Matrix4d info = Eigen::Matrix4d::Zero();
  double max_q = 0, max_v = 0, max_tau = 0;
  for (int k = 0; k < n; ++k) {
    const ReferenceSample3& s = samples[static_cast<std::size_t>(k)];
    const double sign = (s.rate > 0) - (s.rate < 0);
    max_q = std::max(max_q, std::abs(s.position));
    max_v = std::max(max_v, std::abs(s.rate));
    max_tau = std::max(max_tau, std::abs(0.05 * s.acceleration + 0.2 * s.rate + 1.0 * sign + 0.3));
    if (k % 100 == 0 && !left_out[static_cast<std::size_t>(k)]) {
      const Eigen::Vector4d phi(s.acceleration, s.rate, sign, 1.0);
      info += phi * phi.transpose();
    }
  }
  CHECK(max_q <= 1.0);
  CHECK(max_v <= 2.0);
  CHECK(max_tau <= 3.0);
  CHECK(std::max({max_q / 1.0, max_v / 2.0, max_tau / 3.0}) > 0.9);  // a limit binds
  // sigma^2 0.8 / d per decimated sample (every 10th logged one, 100 Hz):
  // Cov = sigma^2 0.08 (sum over the decimated samples)^-1.
  const Eigen::Matrix4d cov = (info / (0.05 * 0.05 * 0.08)).inverse();
  for (int j = 0; j < 4; ++j) {
    CHECK(d.designed.predicted_std[static_cast<std::size_t>(j)] == Approx(std::sqrt(cov(j, j))).epsilon(0.03));
  }
  CHECK(d.designed.geometric_mean_relative_std < d.naive.geometric_mean_relative_std);
}

TEST_CASE("the torque noise comes from an inverse-dynamics fit's residuals, the median over its logs") {
  const double n = NoiseFromIdimResiduals({{"a.csv:tau", 0.01}, {"b.csv:tau", 0.03}, {"c.csv:tau", 0.02}, {"d.csv:q", 9.0}},
                                          {{"c.csv:tau", 1.5}});
  CHECK(n == Approx(0.02 * 1.5 * std::sqrt(12.5)));
  CHECK(NoiseFromIdimResiduals({{"oe.csv:q", 0.001}}, {}) == 0.0);
}
