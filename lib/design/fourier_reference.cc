#include "design/fourier_reference.h"

#include <cmath>
#include <stdexcept>

namespace driveid {

ReferenceSample3 FourierReference::At(double t) const {
  // q(t) = sum_k a_k (cos w_k t - 1) + b_k sin w_k t: the -1 puts the
  // reference at q = 0 at t = 0 (and at every period's start), so a
  // periodic experiment begins and ends where the machine stands; rate and
  // acceleration are its exact derivatives (no differencing).
  ReferenceSample3 s;
  for (std::size_t k = 0; k < harmonics.size(); ++k) {
    const double w = 2.0 * M_PI * harmonics[k] * base_frequency;
    const double c = std::cos(w * t), n = std::sin(w * t);
    s.position += cosine[k] * (c - 1.0) + sine[k] * n;
    s.rate += w * (-cosine[k] * n + sine[k] * c);
    s.acceleration += -w * w * (cosine[k] * c + sine[k] * n);
  }
  return s;
}

std::vector<double> FourierReference::LineFrequencies() const {
  std::vector<double> f;
  for (int n : harmonics) f.push_back(n * base_frequency);
  return f;
}

FourierReference MakeRestingReference(double base_frequency, const std::vector<int>& harmonics,
                                      const std::vector<double>& free) {
  const std::size_t lines = harmonics.size();
  if (lines < 2 || free.size() != 2 * (lines - 1)) throw std::invalid_argument("MakeRestingReference: sizes");
  FourierReference r{base_frequency, harmonics, std::vector<double>(lines, 0.0), std::vector<double>(lines, 0.0)};
  // The design's free coefficients are the higher lines'; the first line's
  // pair is solved so that the reference also starts at rest:
  //   q'(0) = sum_k b_k w_k = 0  and  q''(0) = -sum_k a_k w_k^2 = 0
  // (in units of the base frequency, which cancels). A machine started from
  // standstill then needs no step in speed or torque.
  double rate0 = 0.0, acceleration0 = 0.0;
  const double w1 = harmonics[0];
  for (std::size_t k = 1; k < lines; ++k) {
    r.cosine[k] = free[k - 1];
    r.sine[k] = free[lines - 1 + k - 1];
    const double w = harmonics[k];
    acceleration0 += r.cosine[k] * w * w;
    rate0 += r.sine[k] * w;
  }
  r.cosine[0] = -acceleration0 / (w1 * w1);
  r.sine[0] = -rate0 / w1;
  return r;
}

FourierReference ScaledReference(FourierReference reference, double scale) {
  for (auto& a : reference.cosine) a *= scale;
  for (auto& b : reference.sine) b *= scale;
  return reference;
}

}  // namespace driveid
