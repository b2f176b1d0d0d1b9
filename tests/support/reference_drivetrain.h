// An independent implementation of docs/models.md#drive-train for recovery tests: written from
// the equations without the library's model or simulator code. Fixed-step
// classical Runge-Kutta on fine substeps; stick, reversal and break-away
// located by bisection on the substep. The test data are made with this, so
// a mistake shared by the library's model and simulator cannot hide.
#pragma once

#include <utility>
#include <vector>

namespace reference {

struct DriveTrain {
  bool full = false;
  double n_g = 80, k_Tl = 15000, k_Tg = 18375;
  double J = 0.413;   // n_g^2 Theta_motor [kg m^2]
  double Jg = 0.043;  // n_g^2 Theta_g
  double d_g = 0.016, tau_c = 5.0;
};

struct Log {
  std::vector<double> t, tau_motor, tau_link;
  std::vector<double> q_motor;  ///< motor encoder n_g phi [rad], noise-free
  std::vector<double> q_link;   ///< gear output (link root) angle Delta [rad], noise-free
};

/// Step of `amplitude` N m at `step_time`, sampled at `rate` Hz for `duration` s,
/// link torque plus `offset` and Gaussian noise of std `sigma` from `seed`,
/// AR(1) with lag-1 correlation `rho` (e_k = rho e_{k-1} + sqrt(1 - rho^2) sigma w_k;
/// rho 0: white, the same draws).
Log SimulateStep(const DriveTrain& d, double rate, double duration, double step_time, double amplitude,
                 double sigma, double offset, unsigned seed, double rho = 0.0);

/// A torque held in steps: `levels[i].second` N m from `levels[i].first` s
/// on (times ascending; 0 N m before the first), otherwise as SimulateStep.
Log SimulateSteps(const DriveTrain& d, double rate, double duration, const std::vector<std::pair<double, double>>& levels,
                  double sigma, double offset, unsigned seed, double rho = 0.0);

}  // namespace reference
