#include "signal/lagged_products.h"

#include <complex>

#include <unsupported/Eigen/FFT>

namespace driveid {

std::vector<double> LaggedProducts(const std::vector<double>& x, std::size_t max_lag) {
  std::size_t padded = 2;  // kissfft's one-point plan indexes an empty buffer
  while (padded < x.size() + max_lag) padded *= 2;
  std::vector<double> signal(x);
  signal.resize(padded, 0.0);
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> spectrum;
  fft.fwd(spectrum, signal);
  for (auto& c : spectrum) c = std::norm(c);
  std::vector<double> correlation;
  fft.inv(correlation, spectrum);
  correlation.resize(max_lag + 1);
  return correlation;
}

}  // namespace driveid
