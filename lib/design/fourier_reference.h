// A periodic position reference as a finite Fourier series that starts and
// ends at rest (docs/models.md#excitation-design):
//   q(t) = sum_k a_k (cos(w_k t) - 1) + b_k sin(w_k t),  w_k = 2 pi n_k f_0,
// so q(0) = 0; the first line's coefficients are set by the others so that
// q'(0) = sum_k b_k w_k = 0 and q''(0) = -sum_k a_k w_k^2 = 0. Every line is
// a harmonic of f_0 = 1 / period: the reference repeats with the period.
#pragma once

#include <vector>

namespace driveid {

struct ReferenceSample3 {
  double position = 0.0, rate = 0.0, acceleration = 0.0;
};

struct FourierReference {
  double base_frequency = 0.0;  ///< f_0 [Hz]: 1 / period
  std::vector<int> harmonics;   ///< n_k (ascending, distinct, > 0)
  std::vector<double> cosine;   ///< a_k [rad or m]
  std::vector<double> sine;     ///< b_k [rad or m]

  /// q, q', q'' at time t [s].
  ReferenceSample3 At(double t) const;
  /// The frequencies n_k f_0 [Hz].
  std::vector<double> LineFrequencies() const;
};

/// The reference whose lines 2.. have the coefficients `free` (a_2.., then
/// b_2..; 2 (K - 1) values) and whose first line makes it start at rest.
FourierReference MakeRestingReference(double base_frequency, const std::vector<int>& harmonics,
                                      const std::vector<double>& free);

/// The same reference with every coefficient times `scale`.
FourierReference ScaledReference(FourierReference reference, double scale);

}  // namespace driveid
