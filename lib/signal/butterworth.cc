#include "signal/butterworth.h"

#include <algorithm>
#include <cmath>

namespace driveid {
namespace {

struct Biquad {
  double b0, b1, b2, a1, a2;
};

// Second-order Butterworth low-pass by the bilinear transform.
Biquad Design(double cutoff, double rate) {
  const double k = std::tan(M_PI * cutoff / rate);  // pre-warped
  const double q = 1.0 / std::sqrt(2.0);
  const double norm = 1.0 / (1.0 + k / q + k * k);
  const double b0 = k * k * norm;
  return {b0, 2.0 * b0, b0, 2.0 * (k * k - 1.0) * norm, (1.0 - k / q + k * k) * norm};
}

void Run(const Biquad& f, std::vector<double>& x) {
  // Direct form II transposed, started at the steady state of x[0].
  const double gain_state = x.front();
  double z1 = gain_state * (1.0 - f.b0), z2 = gain_state * (f.b2 - f.a2);
  for (double& value : x) {
    const double in = value;
    const double out = f.b0 * in + z1;
    z1 = f.b1 * in - f.a1 * out + z2;
    z2 = f.b2 * in - f.a2 * out;
    value = out;
  }
}

}  // namespace

std::vector<double> ZeroPhaseLowPass(const std::vector<double>& signal, double cutoff, double rate) {
  const std::size_t n = signal.size();
  if (n < 2) return signal;
  const Biquad f = Design(cutoff, rate);
  // Odd reflection of about three time constants at each end.
  const std::size_t pad = std::min<std::size_t>(n - 1, static_cast<std::size_t>(std::ceil(3.0 * rate / cutoff)) + 1);
  std::vector<double> x;
  x.reserve(n + 2 * pad);
  for (std::size_t i = pad; i >= 1; --i) x.push_back(2.0 * signal.front() - signal[i]);
  x.insert(x.end(), signal.begin(), signal.end());
  for (std::size_t i = 1; i <= pad; ++i) x.push_back(2.0 * signal.back() - signal[n - 1 - i]);
  Run(f, x);
  std::reverse(x.begin(), x.end());
  Run(f, x);
  std::reverse(x.begin(), x.end());
  return std::vector<double>(x.begin() + static_cast<std::ptrdiff_t>(pad), x.begin() + static_cast<std::ptrdiff_t>(pad + n));
}

double ConstantRate(const std::vector<double>& time, double tolerance) {
  if (time.size() < 2) return 0.0;
  const double mean = (time.back() - time.front()) / static_cast<double>(time.size() - 1);
  for (std::size_t k = 1; k < time.size(); ++k) {
    if (std::abs(time[k] - time[k - 1] - mean) > tolerance * mean) return 0.0;
  }
  return 1.0 / mean;
}

}  // namespace driveid
