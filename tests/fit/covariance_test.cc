// fit/core/covariance.h: the prewhitened long-run covariance. Its G makes the
// score identity sum_t J_t r_t = sum_s G_s u_s exact (u_t = r_t - rho
// r_(t-1), rho the prewhitening one); for a constant regressor and AR(1) errors of innovation
// variance s^2 it is the closed-form long-run variance n s^2 / (1 - rho)^2;
// for white errors it is the plain sum of squares.
#include "fit/core/covariance.h"

#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include "signal/lagged_products.h"

using namespace driveid;

TEST_CASE("long-run covariance: G makes the score identity exact") {
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss;
  const int n = 400;
  RowMatrix j(n, 2);
  Eigen::VectorXd r(n);
  double previous = 0.0;
  for (int t = 0; t < n; ++t) {
    j(t, 0) = std::sin(0.05 * t);
    j(t, 1) = 1.0 + 0.01 * t;
    previous = 0.7 * previous + gauss(rng);
    r(t) = previous;
  }
  const Eigen::VectorXd score = j.transpose() * r;
  RowMatrix g = j;
  const LongRunCovariance c = CalcLongRunCovarianceInPlace(g, r);
  CHECK(c.autocorrelation > 0.55);
  CHECK(c.autocorrelation < 0.85);
  // The prewhitening rho (phased in above lag-1 0.5, covariance.cc) read
  // back from G's last step; G then follows G_s = J_s + rho G_(s+1) and the
  // score identity holds exactly.
  const double rho = (g(n - 2, 1) - j(n - 2, 1)) / j(n - 1, 1);
  CHECK(rho > 0.0);
  CHECK(rho < c.autocorrelation + 0.05);
  for (int t = 0; t + 1 < n; ++t) CHECK(g(t, 0) == Approx(j(t, 0) + rho * g(t + 1, 0)).margin(1e-12));
  Eigen::VectorXd u(n);
  for (int t = 0; t < n; ++t) u(t) = r(t) - (t > 0 ? rho * r(t - 1) : 0.0);
  const Eigen::VectorXd whitened = g.transpose() * u;
  CHECK(whitened(0) == Approx(score(0)).epsilon(1e-9));
  CHECK(whitened(1) == Approx(score(1)).epsilon(1e-9));
  // The same covariance whether or not the Jacobian is overwritten.
  const LongRunCovariance copy = CalcLongRunCovariance(j, r);
  CHECK((copy.covariance - c.covariance).norm() <= 1e-9 * c.covariance.norm());
}

TEST_CASE("long-run covariance: AR(1) errors under a constant regressor give n s^2 / (1 - rho)^2") {
  std::mt19937 rng(11);
  std::normal_distribution<double> gauss;
  const int n = 40000;
  const double rho = 0.9, s = 0.5;
  RowMatrix j = RowMatrix::Ones(n, 1);
  Eigen::VectorXd r(n);
  double previous = 0.0;
  for (int t = 0; t < n; ++t) r(t) = previous = rho * previous + s * gauss(rng);
  const LongRunCovariance c = CalcLongRunCovariance(j, r);
  const double expected = n * s * s / ((1.0 - rho) * (1.0 - rho));
  CHECK(c.autocorrelation == Approx(rho).margin(0.01));
  CHECK(c.covariance(0, 0) == Approx(expected).epsilon(0.1));
  // White errors: the plain sum of squares n s^2 (no inflation).
  for (int t = 0; t < n; ++t) r(t) = s * gauss(rng);
  const LongRunCovariance white = CalcLongRunCovariance(j, r);
  CHECK(white.covariance(0, 0) == Approx(n * s * s).epsilon(0.05));
}

TEST_CASE("lagged products: r(l) = sum_t x_t x_(t+l), exact against the direct sum") {
  std::vector<double> x;
  for (int t = 0; t < 37; ++t) x.push_back(std::cos(0.3 * t) + 0.1 * t);
  const std::vector<double> r = LaggedProducts(x, 20);
  REQUIRE(r.size() == 21);
  for (std::size_t l = 0; l <= 20; ++l) {
    double direct = 0.0;
    for (std::size_t t = 0; t + l < x.size(); ++t) direct += x[t] * x[t + l];
    CHECK(r[l] == Approx(direct).epsilon(1e-10).margin(1e-10));
  }
}

TEST_CASE("lagged products of one sample and of none (a one-point FFT used to crash)") {
  const std::vector<double> one = LaggedProducts({3.0}, 0);
  REQUIRE(one.size() == 1);
  CHECK(one[0] == Approx(9.0));
  const std::vector<double> none = LaggedProducts({}, 0);
  REQUIRE(none.size() == 1);
  CHECK(none[0] == Approx(0.0).margin(1e-15));
}
