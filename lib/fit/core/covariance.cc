#include "fit/core/covariance.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include <Eigen/Dense>
#include <unsupported/Eigen/FFT>

#include "signal/lagged_products.h"

namespace driveid {

namespace {

// Above this bandwidth the lag sum goes through the FFT: the direct sum
// costs n p^2 per lag, and an output-error fit whose residuals have lag-1
// 0.999 asks for thousands of lags (25 000 samples: 3 300 lags, half the
// fit's time).
constexpr int kDirectLagSumMax = 32;

// sum_{l=1..L} c_l (M_l + M_l'), M_l = sum_t g_{t+l} g_t' (p x p), as
// S + S' with S = H' G and H's column i the correlation
// h_i(t) = sum_l c_l g_{t+l,i}, computed for all t at once by the FFT with
// zero padding to N >= n + L (no wrap-around). Equals the direct sum to
// rounding (tests/fit/least_squares_test.cc).
Eigen::MatrixXd LagSumByFft(const Eigen::Ref<const RowMatrix>& g, const std::vector<double>& c) {
  const Eigen::Index n = g.rows();
  const Eigen::Index lags = static_cast<Eigen::Index>(c.size()) - 1;  // c[0] unused
  Eigen::Index size = 1;
  while (size < n + lags) size *= 2;
  Eigen::FFT<double> fft;
  std::vector<double> kernel(static_cast<std::size_t>(size), 0.0);
  // h(t) = sum_l c_l g(t + l) is the circular convolution of g with k(m) = c_{-m}.
  for (Eigen::Index l = 1; l <= lags; ++l) kernel[static_cast<std::size_t>((size - l) % size)] = c[l];
  std::vector<std::complex<double>> kernel_spectrum;
  fft.fwd(kernel_spectrum, kernel);
  Eigen::MatrixXd h(n, g.cols());
  std::vector<double> column(static_cast<std::size_t>(size));
  std::vector<std::complex<double>> spectrum;
  std::vector<double> filtered;
  for (Eigen::Index i = 0; i < g.cols(); ++i) {
    std::fill(column.begin(), column.end(), 0.0);
    for (Eigen::Index t = 0; t < n; ++t) column[static_cast<std::size_t>(t)] = g(t, i);
    fft.fwd(spectrum, column);
    for (std::size_t k = 0; k < spectrum.size(); ++k) spectrum[k] *= kernel_spectrum[k];
    fft.inv(filtered, spectrum);
    for (Eigen::Index t = 0; t < n; ++t) h(t, i) = filtered[static_cast<std::size_t>(t)];
  }
  const Eigen::MatrixXd sum = h.transpose() * g;
  return sum + sum.transpose();
}

// sum_{|l|<=L} w_l gamma_u(l) sum_t G_t' G_{t-l} with Bartlett weights and
// Andrews' AR(1) plug-in bandwidth for lag-1 autocorrelation `lag1`.
Eigen::MatrixXd BartlettCovariance(const Eigen::Ref<const RowMatrix>& g, const Eigen::VectorXd& u, double lag1,
                                   int& bandwidth_out) {
  const Eigen::Index n = u.size();
  const double r0 = u.squaredNorm();
  Eigen::MatrixXd covariance = (r0 / static_cast<double>(n)) * (g.transpose() * g);
  bandwidth_out = 0;
  if (n < 3 || r0 <= 0.0) return covariance;
  // Kept inside (-0.999, 0.999) so that alpha stays finite.
  const double rho = std::clamp(lag1, -0.999, 0.999);
  const double alpha = 4.0 * rho * rho / ((1.0 - rho) * (1.0 - rho) * (1.0 + rho) * (1.0 + rho));
  const double bandwidth = 1.1447 * std::cbrt(alpha * static_cast<double>(n));
  bandwidth_out = static_cast<int>(std::min<double>(std::floor(bandwidth), static_cast<double>(n - 1)));
  if (bandwidth_out > kDirectLagSumMax) {
    // c_l = w_l gamma_l, gamma_l = sum_t u_t u_{t+l} / n.
    std::vector<double> c = LaggedProducts(std::vector<double>(u.data(), u.data() + n), bandwidth_out);
    c[0] = 0.0;
    for (int lag = 1; lag <= bandwidth_out; ++lag) {
      const std::size_t l = static_cast<std::size_t>(lag);
      c[l] = (1.0 - static_cast<double>(lag) / (bandwidth_out + 1.0)) * (c[l] / static_cast<double>(n));
    }
    return covariance + LagSumByFft(g, c);
  }
  for (int lag = 1; lag <= bandwidth_out; ++lag) {
    const double weight = 1.0 - static_cast<double>(lag) / (bandwidth_out + 1.0);
    const double gamma = u.head(n - lag).dot(u.tail(n - lag)) / static_cast<double>(n);
    const Eigen::MatrixXd m = g.bottomRows(n - lag).transpose() * g.topRows(n - lag);
    covariance += weight * gamma * (m + m.transpose());
  }
  return covariance;
}

}  // namespace

LongRunCovariance CalcLongRunCovariance(const Eigen::Ref<const RowMatrix>& jacobian,
                                        const Eigen::Ref<const Eigen::VectorXd>& residuals) {
  RowMatrix g = jacobian;
  return CalcLongRunCovarianceInPlace(g, residuals);
}

LongRunCovariance CalcLongRunCovarianceInPlace(Eigen::Ref<RowMatrix> g,
                                               const Eigen::Ref<const Eigen::VectorXd>& residuals) {
  LongRunCovariance out;
  const Eigen::Index n = residuals.size();
  const Eigen::Index p = g.cols();
  out.covariance = Eigen::MatrixXd::Zero(p, p);
  if (n == 0) return out;
  const double r0 = residuals.squaredNorm();
  if (n >= 3 && r0 > 0.0) out.autocorrelation = residuals.head(n - 1).dot(residuals.tail(n - 1)) / r0;
  // AR(1) prewhitening, exact: with u_0 = e_0 and u_t = e_t - rho e_{t-1},
  // e_t = sum_{k<=t} rho^(t-k) u_k, so the score sum_t J_t' e_t equals
  // sum_s G_s' u_s with G_s = sum_{t>=s} rho^(t-s) J_t (G_s = J_s + rho G_{s+1}).
  // The nearly white u then needs only a short Bartlett window; truncating
  // the slowly decaying autocovariances of e itself under-covers (offset at
  // lag-1 0.99: 86 % instead of 95 %).
  // Prewhitening is phased in between lag-1 0.5 and 0.8: below, the plain
  // Bartlett estimate covers (Monte Carlo) and a small rho would only make u
  // over-differenced, whose negative autocovariances a short window drops.
  // The lag-1 estimate of a short, persistent series is biased low by about
  // (1 + 3 rho) / n (Kendall 1954), and 1/(1 - rho)^2 magnifies that: the
  // prewhitening rho is corrected for it.
  const double weight = std::clamp((out.autocorrelation - 0.5) / 0.3, 0.0, 1.0);
  const double corrected = out.autocorrelation + (1.0 + 3.0 * out.autocorrelation) / static_cast<double>(n);
  const double rho = weight * std::clamp(corrected, -0.99, 0.99);
  Eigen::VectorXd u = residuals;
  for (Eigen::Index t = n - 1; t >= 1; --t) u(t) = residuals(t) - rho * residuals(t - 1);
  for (Eigen::Index t = n - 2; t >= 0; --t) g.row(t) += rho * g.row(t + 1);
  // The window is the one the residuals themselves call for: prewhitened u
  // keeps the rest of their correlation (often negative lags after the
  // AR(1) step), which a window sized for u alone would drop.
  out.covariance = BartlettCovariance(g, u, out.autocorrelation, out.bandwidth);
  return out;
}

}  // namespace driveid
