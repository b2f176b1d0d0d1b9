// Deterministic Gaussian noise: mt19937_64 (fully specified by the C++
// standard) with a Box-Muller transform written here, so that the same seed
// gives the same numbers with every standard library.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>

namespace driveid {

class GaussianNoise {
 public:
  explicit GaussianNoise(std::uint64_t seed) : engine_(seed) {}

  /// Next sample of N(0, sigma^2).
  double Next(double sigma) {
    if (has_spare_) {
      has_spare_ = false;
      return sigma * spare_;
    }
    // Two uniforms in (0, 1]: 53 random bits each.
    const double u1 = (static_cast<double>(engine_() >> 11) + 1.0) * 0x1.0p-53;
    const double u2 = static_cast<double>(engine_() >> 11) * 0x1.0p-53;
    const double radius = std::sqrt(-2.0 * std::log(u1));
    const double angle = 6.283185307179586 * u2;
    spare_ = radius * std::sin(angle);
    has_spare_ = true;
    return sigma * radius * std::cos(angle);
  }

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace driveid
