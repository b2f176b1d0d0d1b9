#include "sim/cvodes_integrator.h"

#include <cvodes/cvodes.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_config.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"

namespace driveid {

bool IntegratorOptions::IsValid(std::string* error) const {
  OptionCheck check(error);
  check.Require(Positive(relative_tolerance) && relative_tolerance < 1.0, "relative_tolerance", relative_tolerance,
                "0 < tolerance < 1")
      .Require(max_steps >= 1, "max_steps", static_cast<double>(max_steps), ">= 1");
  for (const double a : absolute_tolerance) check.Require(Positive(a), "absolute_tolerance", a, "> 0 per state");
  for (const double s : parameter_scale) check.Require(Positive(s), "parameter_scale", s, "> 0 per parameter");
  return check;
}
namespace {

// CVODES reports details through an error handler; keep the last message
// (the library prints nothing) and put it into the exception. SUNDIALS 7
// replaced CVodeSetErrHandlerFn by handlers on the context (whose default
// prints to stderr: it is cleared first).
#if SUNDIALS_VERSION_MAJOR >= 7
void CaptureError(int, const char* function, const char*, const char* message, SUNErrCode, void* user_data,
                  SUNContext) {
  *static_cast<std::string*>(user_data) = fmt::format("{}: {}", function, message);
}
#else
void CaptureError(int, const char* module, const char* function, char* message, void* user_data) {
  *static_cast<std::string*>(user_data) = fmt::format("{} {}: {}", module, function, message);
}
#endif

void Check(int code, const char* function, const std::string* detail = nullptr) {
  if (code >= 0) return;
  if (detail != nullptr && !detail->empty()) {
    throw IdentificationError(fmt::format("integrator: {} failed with code {} ({})", function, code, *detail));
  }
  throw IdentificationError(fmt::format("integrator: {} failed with code {}", function, code));
}

template <typename T>
T* CheckPointer(T* pointer, const char* function) {
  if (pointer == nullptr) throw IdentificationError(fmt::format("integrator: {} returned null", function));
  return pointer;
}

int RightHandSide(sunrealtype t, N_Vector y, N_Vector ydot, void* user_data) {
  try {
    static_cast<const SensitivityOdeSystem*>(user_data)->CalcDerivatives(t, N_VGetArrayPointer(y),
                                                                         N_VGetArrayPointer(ydot));
    return 0;
  } catch (...) {
    return -1;
  }
}

int Jacobian(sunrealtype t, N_Vector y, N_Vector, SUNMatrix jac, void* user_data, N_Vector, N_Vector, N_Vector) {
  try {
    static_cast<const SensitivityOdeSystem*>(user_data)->CalcStateJacobian(t, N_VGetArrayPointer(y),
                                                                           SUNDenseMatrix_Data(jac));
    return 0;
  } catch (...) {
    return -1;
  }
}

int SensitivityRightHandSide(int, sunrealtype t, N_Vector y, N_Vector, int j, N_Vector ys, N_Vector ysdot,
                             void* user_data, N_Vector, N_Vector) {
  try {
    static_cast<const SensitivityOdeSystem*>(user_data)->CalcSensitivityDerivative(
        t, N_VGetArrayPointer(y), j, N_VGetArrayPointer(ys), N_VGetArrayPointer(ysdot));
    return 0;
  } catch (...) {
    return -1;
  }
}

int Roots(sunrealtype t, N_Vector y, sunrealtype* g, void* user_data) {
  try {
    static_cast<const SensitivityOdeSystem*>(user_data)->CalcRoots(t, N_VGetArrayPointer(y), g);
    return 0;
  } catch (...) {
    return -1;
  }
}

}  // namespace

struct CvodesIntegrator::Handles {
  SUNContext context = nullptr;
  N_Vector state = nullptr;
  N_Vector absolute_tolerance = nullptr;
  N_Vector* sensitivities = nullptr;
  int sensitivity_count = 0;
  SUNMatrix matrix = nullptr;
  SUNLinearSolver linear_solver = nullptr;
  void* memory = nullptr;
  std::string last_error;

  ~Handles() {
    if (memory) CVodeFree(&memory);
    if (linear_solver) SUNLinSolFree(linear_solver);
    if (matrix) SUNMatDestroy(matrix);
    if (sensitivities) N_VDestroyVectorArray(sensitivities, sensitivity_count);
    if (absolute_tolerance) N_VDestroy(absolute_tolerance);
    if (state) N_VDestroy(state);
    if (context) SUNContext_Free(&context);
  }
};

CvodesIntegrator::CvodesIntegrator(const SensitivityOdeSystem& system, const IntegratorOptions& options)
    : handles_(std::make_unique<Handles>()), system_(system) {
  RequireValid(options);
  Handles& h = *handles_;
  const int n = system.state_size();
#if SUNDIALS_VERSION_MAJOR >= 7
  Check(SUNContext_Create(SUN_COMM_NULL, &h.context), "SUNContext_Create");
  Check(SUNContext_ClearErrHandlers(h.context), "SUNContext_ClearErrHandlers");
  Check(SUNContext_PushErrHandler(h.context, CaptureError, &h.last_error), "SUNContext_PushErrHandler");
#else
  Check(SUNContext_Create(nullptr, &h.context), "SUNContext_Create");
#endif
  h.state = CheckPointer(N_VNew_Serial(n, h.context), "N_VNew_Serial");
  N_VConst(0.0, h.state);
  h.absolute_tolerance = CheckPointer(N_VNew_Serial(n, h.context), "N_VNew_Serial");
  for (int i = 0; i < n; ++i) {
    NV_Ith_S(h.absolute_tolerance, i) =
        options.absolute_tolerance.empty() ? 1e-12 : options.absolute_tolerance[static_cast<std::size_t>(i)];
  }
  // Adams-Moulton with Newton iteration: the drive trains are lightly damped
  // oscillators, not stiff, and Adams keeps their oscillations undamped.
  h.memory = CheckPointer(CVodeCreate(CV_ADAMS, h.context), "CVodeCreate");
#if SUNDIALS_VERSION_MAJOR < 7
  Check(CVodeSetErrHandlerFn(h.memory, CaptureError, &h.last_error), "CVodeSetErrHandlerFn");
#endif
  Check(CVodeInit(h.memory, RightHandSide, 0.0, h.state), "CVodeInit");
  Check(CVodeSetUserData(h.memory, const_cast<SensitivityOdeSystem*>(&system)), "CVodeSetUserData");
  Check(CVodeSVtolerances(h.memory, options.relative_tolerance, h.absolute_tolerance), "CVodeSVtolerances");
  Check(CVodeSetMaxNumSteps(h.memory, options.max_steps), "CVodeSetMaxNumSteps");
  h.matrix = CheckPointer(SUNDenseMatrix(n, n, h.context), "SUNDenseMatrix");
  h.linear_solver = CheckPointer(SUNLinSol_Dense(h.state, h.matrix, h.context), "SUNLinSol_Dense");
  Check(CVodeSetLinearSolver(h.memory, h.linear_solver, h.matrix), "CVodeSetLinearSolver");
  Check(CVodeSetJacFn(h.memory, Jacobian), "CVodeSetJacFn");
  if (system.root_count() > 0) {
    Check(CVodeRootInit(h.memory, system.root_count(), Roots), "CVodeRootInit");
    Check(CVodeSetNoInactiveRootWarn(h.memory), "CVodeSetNoInactiveRootWarn");
  }
  root_directions_.assign(static_cast<std::size_t>(system.root_count()), 0);

  h.sensitivity_count = system.sensitivity_count();
  if (h.sensitivity_count > 0) {
    h.sensitivities = CheckPointer(N_VCloneVectorArray(h.sensitivity_count, h.state), "N_VCloneVectorArray");
    for (int j = 0; j < h.sensitivity_count; ++j) N_VConst(0.0, h.sensitivities[j]);
    Check(CVodeSensInit1(h.memory, h.sensitivity_count, CV_STAGGERED, SensitivityRightHandSide, h.sensitivities),
          "CVodeSensInit1");
    std::vector<sunrealtype> absolute(static_cast<std::size_t>(h.sensitivity_count));
    // Sensitivity j is measured in state units per unit of p_j: its absolute
    // tolerance is the state's, divided by the parameter's scale. CVODES
    // takes one scalar per sensitivity; use the smallest state tolerance.
    double smallest = 1e300;
    for (int i = 0; i < n; ++i) smallest = std::min(smallest, NV_Ith_S(h.absolute_tolerance, i));
    for (int j = 0; j < h.sensitivity_count; ++j) {
      const double scale = options.parameter_scale.empty() ? 1.0 : options.parameter_scale[static_cast<std::size_t>(j)];
      absolute[static_cast<std::size_t>(j)] = smallest / (scale > 0.0 ? scale : 1.0);
    }
    Check(CVodeSensSStolerances(h.memory, options.relative_tolerance, absolute.data()), "CVodeSensSStolerances");
    // Sensitivities ride on the state's step control instead of adding their
    // own error test: they feed the Gauss-Newton Jacobian and the covariance,
    // where 1e-4 relative error is irrelevant, and the fits run 1.4-2x faster.
    // tests/sim/drivetrain_simulator_test checks them against finite differences.
    Check(CVodeSetSensErrCon(h.memory, SUNFALSE), "CVodeSetSensErrCon");
    Check(CVodeSensToggleOff(h.memory), "CVodeSensToggleOff");
  }
}

CvodesIntegrator::~CvodesIntegrator() = default;

void CvodesIntegrator::Restart(double t0, const double* x0, const std::vector<const double*>& s0,
                               bool with_sensitivities) {
  Handles& h = *handles_;
  const int n = system_.state_size();
  double* state = N_VGetArrayPointer(h.state);
  for (int i = 0; i < n; ++i) state[i] = x0[i];
  Check(CVodeReInit(h.memory, t0, h.state), "CVodeReInit");
  sensitivities_on_ = with_sensitivities && h.sensitivity_count > 0;
  if (sensitivities_on_) {
    for (int j = 0; j < h.sensitivity_count; ++j) {
      double* s = N_VGetArrayPointer(h.sensitivities[j]);
      const double* source = static_cast<std::size_t>(j) < s0.size() ? s0[static_cast<std::size_t>(j)] : nullptr;
      for (int i = 0; i < n; ++i) s[i] = source ? source[i] : 0.0;
    }
    Check(CVodeSensReInit(h.memory, CV_STAGGERED, h.sensitivities), "CVodeSensReInit");
  } else if (h.sensitivity_count > 0) {
    Check(CVodeSensToggleOff(h.memory), "CVodeSensToggleOff");
  }
  time_ = t0;
  steps_since_restart_ = 0;
  std::fill(root_directions_.begin(), root_directions_.end(), 0);
}

bool CvodesIntegrator::Advance(double t_out, double t_stop) {
  Handles& h = *handles_;
  Check(CVodeSetStopTime(h.memory, t_stop), "CVodeSetStopTime");
  sunrealtype reached = time_;
  h.last_error.clear();
  const int flag = CVode(h.memory, t_out, h.state, &reached, CV_NORMAL);
  Check(flag, "CVode", &h.last_error);
  time_ = reached;
  long steps = 0;  // since the last CVodeReInit, which zeroes the counter
  Check(CVodeGetNumSteps(h.memory, &steps), "CVodeGetNumSteps");
  total_steps_ += steps - steps_since_restart_;
  steps_since_restart_ = steps;
  if (sensitivities_on_) {
    sunrealtype sensitivity_time = 0.0;
    Check(CVodeGetSens(h.memory, &sensitivity_time, h.sensitivities), "CVodeGetSens");
  }
  if (flag == CV_ROOT_RETURN) {
    Check(CVodeGetRootInfo(h.memory, root_directions_.data()), "CVodeGetRootInfo");
    return true;
  }
  std::fill(root_directions_.begin(), root_directions_.end(), 0);
  return false;
}

long CvodesIntegrator::step_count() const { return total_steps_; }

const double* CvodesIntegrator::state() const { return N_VGetArrayPointer(handles_->state); }

const double* CvodesIntegrator::sensitivity(int j) const {
  return N_VGetArrayPointer(handles_->sensitivities[j]);
}

}  // namespace driveid
