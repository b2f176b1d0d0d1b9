#include "support/reference_cdrive.h"

#include <cmath>
#include <random>

namespace reference {
namespace {
double Sign(double x) { return x > 0 ? 1.0 : (x < 0 ? -1.0 : 0.0); }

// 4-5-6-7 polynomial and its derivatives in nondimensional time.
void Polynomial(double x, double* s, double* ds, double* dds) {
  *s = x * x * x * x * (35 + x * (-84 + x * (70 - 20 * x)));
  *ds = x * x * x * (140 + x * (-420 + x * (420 - 140 * x)));
  *dds = x * x * (420 + x * (-1680 + x * (2100 - 840 * x)));
}
}  // namespace

CDriveLog SimulateProgram(const CDrive& d, double alpha_left, double alpha_right, double stroke, int cycles,
                          double rate, double sigma, unsigned seed) {
  std::mt19937 engine(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  const double quantum = 2 * M_PI / 8192;
  const double k = d.p * d.p / (16 * M_PI * M_PI);
  const double a = d.I_h + d.I_c / 4 + k * d.m, b = d.I_c / 4 - k * d.m;
  CDriveLog log;
  const long samples = std::lround(2 * stroke * cycles * rate) + 1;
  for (long n = 0; n < samples; ++n) {
    const double t = static_cast<double>(n) / rate;
    double phase = std::fmod(t, 2 * stroke) / stroke;  // 0..2
    double s, ds, dds, direction = 1.0;
    if (phase > 1.0) {
      phase = 2.0 - phase;
      direction = -1.0;
    }
    Polynomial(phase, &s, &ds, &dds);
    const double rate_scale = direction / stroke, acceleration_scale = 1.0 / (stroke * stroke);
    const double wl = alpha_left * ds * rate_scale, wr = alpha_right * ds * rate_scale;
    const double al = alpha_left * dds * acceleration_scale, ar = alpha_right * dds * acceleration_scale;
    // (28): M psi'' + C psi' + phi_c.
    const double tl = a * al + b * ar + (d.beta + d.gamma / 2) * wl - d.gamma / 2 * wr + d.delta * Sign(wl) +
                      d.eta * Sign(wl - wr);
    const double tr = b * al + a * ar - d.gamma / 2 * wl + (d.beta + d.gamma / 2) * wr + d.delta * Sign(wr) +
                      d.eta * Sign(wr - wl);
    log.t.push_back(t);
    log.psi_L.push_back(std::floor(alpha_left * s / quantum) * quantum);
    log.psi_R.push_back(std::floor(alpha_right * s / quantum) * quantum);
    log.tau_L.push_back(tl + noise(engine));
    log.tau_R.push_back(tr + noise(engine));
  }
  return log;
}

}  // namespace reference
