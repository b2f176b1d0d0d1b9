// One bin of the discrete Fourier transform, summed directly (no FFT): the
// tests' independent reading of a periodic signal's lines.
#pragma once

#include <cmath>
#include <complex>
#include <cstddef>
#include <vector>

namespace driveid::testing {

/// sum_k x[k] exp(-2 pi i bin k / n) over the first n samples of x.
inline std::complex<double> DftBin(const std::vector<double>& x, std::size_t n, int bin) {
  std::complex<double> sum = 0.0;
  for (std::size_t k = 0; k < n; ++k) sum += x[k] * std::polar(1.0, -2.0 * M_PI * bin * static_cast<double>(k) / n);
  return sum;
}

/// The amplitude of line `bin` of one period of n samples: 2 |X_bin| / n.
inline double LineAmplitude(const std::vector<double>& x, std::size_t n, int bin) {
  return 2.0 * std::abs(DftBin(x, n, bin)) / static_cast<double>(n);
}

}  // namespace driveid::testing
