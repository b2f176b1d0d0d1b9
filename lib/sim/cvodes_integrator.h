// Thin RAII owner of a CVODES integrator with forward sensitivities and root
// finding. The system is described by SensitivityOdeSystem; the integrator
// owns the SUNDIALS context, vectors, dense matrix, linear solver and the
// solver memory. Every SUNDIALS return code goes through one checker that
// throws IdentificationError naming the function and the code. Exceptions
// never cross the C callbacks: they are caught there and turned into a
// negative return code, which the checker then reports.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace driveid {

/// A smooth ODE x' = f(t, x) with parameter sensitivities s_j' = A s_j + b_j
/// and root functions g(t, x). Implementations must not throw from these.
class SensitivityOdeSystem {
 public:
  virtual ~SensitivityOdeSystem() = default;
  virtual int state_size() const = 0;
  virtual int sensitivity_count() const = 0;
  virtual int root_count() const = 0;
  virtual void CalcDerivatives(double t, const double* x, double* dx) const = 0;
  /// Column-major n x n Jacobian df/dx.
  virtual void CalcStateJacobian(double t, const double* x, double* jacobian) const = 0;
  /// s_j' = (df/dx) s_j + df/dp_j.
  virtual void CalcSensitivityDerivative(double t, const double* x, int j, const double* s,
                                         double* ds) const = 0;
  virtual void CalcRoots(double t, const double* x, double* g) const = 0;
};

/// Accuracy settings of the integrator.
struct IntegratorOptions {
  double relative_tolerance = 1e-8;
  std::vector<double> absolute_tolerance;  ///< per state; empty = 1e-12 each
  std::vector<double> parameter_scale;     ///< |p_j| for sensitivity tolerances; empty = 1
  long max_steps = 20000;                  ///< per call to Advance
  /// Every bound on these fields (‹field› names the option); see core/option_check.h.
  bool IsValid(std::string* error) const;
};

class CvodesIntegrator {
 public:
  CvodesIntegrator(const SensitivityOdeSystem& system, const IntegratorOptions& options);
  ~CvodesIntegrator();
  CvodesIntegrator(const CvodesIntegrator&) = delete;
  CvodesIntegrator& operator=(const CvodesIntegrator&) = delete;

  /// Restarts at time t0 from x0 and (if with_sensitivities) s0[j] (each of
  /// length n, nullptr = zeros). Call after any change to the vector field.
  void Restart(double t0, const double* x0, const std::vector<const double*>& s0, bool with_sensitivities);

  /// Integrates towards t_out, never past t_stop. Returns true if a root of
  /// g stopped it (at time(), before t_out), false when t_out was reached.
  bool Advance(double t_out, double t_stop);

  double time() const { return time_; }
  /// Internal steps taken since construction, across restarts (work measure).
  long step_count() const;
  const double* state() const;
  /// Sensitivity j at time() (valid after Advance with sensitivities on).
  const double* sensitivity(int j) const;
  /// Which roots fired at the last root stop: +1 rising, -1 falling, 0 none.
  const std::vector<int>& root_directions() const { return root_directions_; }

 private:
  struct Handles;
  std::unique_ptr<Handles> handles_;
  const SensitivityOdeSystem& system_;
  double time_ = 0.0;
  bool sensitivities_on_ = false;
  long total_steps_ = 0;
  long steps_since_restart_ = 0;
  std::vector<int> root_directions_;
};

}  // namespace driveid
