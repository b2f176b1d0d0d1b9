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

// Direct form II transposed over `count` values from `values` on (step
// `stride`), in place, from state (z1, z2).
void Run(const Biquad& f, double* values, std::size_t count, std::ptrdiff_t stride, double& z1, double& z2) {
  for (std::size_t i = 0; i < count; ++i, values += stride) {
    const double in = *values;
    const double out = f.b0 * in + z1;
    z1 = f.b1 * in - f.a1 * out + z2;
    z2 = f.b2 * in - f.a2 * out;
    *values = out;
  }
}

// The state in which the input `level`, held, gives the output `level`.
void SteadyState(const Biquad& f, double level, double& z1, double& z2) {
  z1 = level * (1.0 - f.b0);
  z2 = level * (f.b2 - f.a2);
}

}  // namespace

void ZeroPhaseLowPassInPlace(std::vector<double>& x, double cutoff, double rate) {
  const std::size_t n = x.size();
  if (n < 2) return;
  const Biquad f = Design(cutoff, rate);
  // The padded sequence is head, x, tail with odd reflections of about three
  // time constants: head[i] = 2 x_0 - x_(pad-i), tail[i] = 2 x_(n-1) - x_(n-2-i).
  // Only the ends are held apart: the forward pass needs head for its state
  // only, the backward pass starts at the end of the filtered tail, and its
  // outputs over head are not part of the result.
  const std::size_t pad = std::min<std::size_t>(n - 1, static_cast<std::size_t>(std::ceil(3.0 * rate / cutoff)) + 1);
  std::vector<double> head(pad), tail(pad);
  for (std::size_t i = 0; i < pad; ++i) {
    head[i] = 2.0 * x.front() - x[pad - i];
    tail[i] = 2.0 * x.back() - x[n - 2 - i];
  }
  double z1 = 0.0, z2 = 0.0;
  SteadyState(f, head.front(), z1, z2);
  Run(f, head.data(), pad, 1, z1, z2);
  Run(f, x.data(), n, 1, z1, z2);
  Run(f, tail.data(), pad, 1, z1, z2);
  SteadyState(f, tail.back(), z1, z2);
  Run(f, tail.data() + pad - 1, pad, -1, z1, z2);
  Run(f, x.data() + n - 1, n, -1, z1, z2);
}

std::vector<double> ZeroPhaseLowPass(const std::vector<double>& signal, double cutoff, double rate) {
  std::vector<double> x = signal;
  ZeroPhaseLowPassInPlace(x, cutoff, rate);
  return x;
}

void FlatZeroPhaseLowPassInPlace(std::vector<double>& x, double cutoff, double rate) {
  ZeroPhaseLowPassInPlace(x, cutoff, rate);
  ZeroPhaseLowPassInPlace(x, cutoff, rate);
  std::vector<double> twice = x;
  ZeroPhaseLowPassInPlace(x, cutoff, rate);
  for (std::size_t k = 0; k < x.size(); ++k) x[k] = 3.0 * twice[k] - 2.0 * x[k];
}

std::vector<double> FlatZeroPhaseLowPass(const std::vector<double>& signal, double cutoff, double rate) {
  std::vector<double> x = signal;
  FlatZeroPhaseLowPassInPlace(x, cutoff, rate);
  return x;
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
