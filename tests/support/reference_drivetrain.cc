#include "support/reference_drivetrain.h"

#include <array>
#include <cmath>
#include <random>

namespace reference {
namespace {

using State = std::array<double, 4>;  // phi, omega, Delta, Delta rate (output side)

struct Plant {
  const DriveTrain& d;
  double u;
  int mode;  // -1, +1 sliding; 0 stuck

  double Keq() const { return d.k_Tl * d.k_Tg / (d.k_Tl + d.k_Tg); }
  double Force(const State& x) const {  // torque the friction has to hold
    return d.full ? d.n_g * u - d.k_Tg * (x[0] - x[2]) : d.n_g * u - Keq() * x[0];
  }
  State Rate(const State& x) const {
    State r{0, 0, 0, 0};
    if (mode != 0) {
      r[0] = x[1];
      r[1] = (Force(x) - d.n_g * d.n_g * d.d_g * x[1] - d.tau_c * mode) / d.J;
    }
    if (d.full) {
      r[2] = x[3];
      r[3] = (d.k_Tg * x[0] - (d.k_Tl + d.k_Tg) * x[2]) / d.Jg;
    }
    return r;
  }
  State Step(const State& x, double h) const {
    auto add = [](const State& a, const State& b, double s) {
      State c;
      for (int i = 0; i < 4; ++i) c[i] = a[i] + s * b[i];
      return c;
    };
    const State k1 = Rate(x), k2 = Rate(add(x, k1, h / 2)), k3 = Rate(add(x, k2, h / 2)), k4 = Rate(add(x, k3, h));
    State out;
    for (int i = 0; i < 4; ++i) out[i] = x[i] + h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    return out;
  }
  // Event function of the current mode: changes sign at a switch.
  bool Switches(const State& after) const {
    if (mode != 0) return after[1] * mode <= 0.0;
    return std::abs(Force(after)) > d.tau_c;
  }
  void Decide(const State& x) {
    const double f = Force(x);
    mode = std::abs(f) <= d.tau_c ? 0 : (f > 0 ? 1 : -1);
  }
};

}  // namespace

Log SimulateStep(const DriveTrain& d, double rate, double duration, double step_time, double amplitude,
                 double sigma, double offset, unsigned seed, double rho) {
  return SimulateSteps(d, rate, duration, {{step_time, amplitude}}, sigma, offset, seed, rho);
}

Log SimulateSteps(const DriveTrain& d, double rate, double duration, const std::vector<std::pair<double, double>>& levels,
                  double sigma, double offset, unsigned seed, double rho) {
  std::mt19937 engine(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  double error = 0.0;
  Log log;
  State x{0, 0, 0, 0};
  Plant plant{d, 0.0, 0};
  const int samples = static_cast<int>(std::lround(duration * rate)) + 1;
  const int substeps = 200;
  for (int k = 0; k < samples; ++k) {
    const double t = k / rate;
    const double link = d.full ? d.k_Tl * x[2] : plant.Keq() * x[0];
    double u = 0.0;
    for (const auto& [from, level] : levels) {
      if (t >= from - 1e-12) u = level;
    }
    log.t.push_back(t);
    log.tau_motor.push_back(u);
    if (sigma > 0) error = k == 0 ? noise(engine) : rho * error + std::sqrt(1.0 - rho * rho) * noise(engine);
    log.tau_link.push_back(link + offset + error);
    log.q_motor.push_back(d.n_g * x[0]);
    log.q_link.push_back(d.full ? x[2] : d.k_Tg / (d.k_Tl + d.k_Tg) * x[0]);
    plant.u = u;
    if (plant.mode == 0 || x[1] == 0.0) plant.Decide(x);
    const double h = 1.0 / rate / substeps;
    for (int s = 0; s < substeps; ++s) {
      double left = 0.0;  // time already covered within this substep
      while (left < h) {
        const State next = plant.Step(x, h - left);
        if (!plant.Switches(next)) {
          x = next;
          break;
        }
        // Bisect for the switching instant within [0, h - left].
        double lo = 0.0, hi = h - left;
        for (int it = 0; it < 60; ++it) {
          const double mid = 0.5 * (lo + hi);
          if (plant.Switches(plant.Step(x, mid))) hi = mid; else lo = mid;
        }
        x = plant.Step(x, hi);
        left += hi;
        if (plant.mode != 0) x[1] = 0.0;
        const int old_mode = plant.mode;
        plant.Decide(x);
        if (old_mode == 0 && plant.mode == 0) {  // numerically at the threshold: break away
          plant.mode = plant.Force(x) > 0 ? 1 : -1;
        }
      }
    }
  }
  return log;
}

}  // namespace reference
