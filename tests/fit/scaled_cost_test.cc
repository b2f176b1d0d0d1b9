// Ceres GradientChecker on the scaled cost of the step fit: the analytic
// Jacobian (CVODES forward sensitivities with jump conditions at stick/slip
// events, times the parameter scales) against Ceres's central differences,
// for the reduced and the full model, away from the truth so that the
// residuals are large and every term matters. The full model integrates the
// undamped link mode throughout, so its differences need a step well above
// the integrator's tolerance (1e-7 relative), as in drivetrain_simulator_test.
#include "fit/scaled_cost.h"

#include <ceres/gradient_checker.h>
#include <ceres/numeric_diff_options.h>

#include <catch2/catch.hpp>

#include "fit/step_fit.h"
#include "support/paper000.h"
#include "support/reference_drivetrain.h"

using namespace driveid;

namespace {

StepLog Log(bool full) {
  reference::DriveTrain truth;
  truth.full = full;
  const auto log = reference::SimulateStep(truth, full ? 5000.0 : 1000.0, 0.2, 0.02, -0.8, 0.1, 0.0, 3);
  return {"ref.csv", log.t, log.tau_motor, log.tau_link, {}, {}};
}

void CheckGradient(DriveTrainModel model, const std::vector<DriveTrainParameter>& free, bool offsets, double step, double tolerance) {
  const std::vector<StepLog> logs = {Log(model == DriveTrainModel::kFull)};
  DriveTrainParameters start = testing_support::PaperDriveTrain();
  start.motor_inertia *= 1.3;
  start.viscous_friction *= 0.7;
  start.coulomb_friction *= 1.4;
  auto residuals = MakeStepResiduals(logs, start, model, free, offsets);
  // Scales as the fit core chooses them: the starting values (1 for an offset).
  std::vector<double> scale, z;
  for (auto parameter : free) scale.push_back(GetDriveTrainParameter(start, parameter));
  if (offsets) scale.push_back(1.0);
  for (std::size_t j = 0; j < scale.size(); ++j) z.push_back(j < free.size() ? 1.0 : 0.3);
  ScaledCost cost(*residuals, scale);
  ceres::NumericDiffOptions numeric;
  // GradientChecker differentiates by Ridders' extrapolation from an initial
  // step: start above the integrator's noise but where the response is
  // still linear (the link mode's phase drifts with Theta_g and k_Tl).
  numeric.ridders_relative_initial_step_size = step;
  const std::vector<const ceres::Manifold*>* no_manifolds = nullptr;
  ceres::GradientChecker checker(&cost, no_manifolds, numeric);
  ceres::GradientChecker::ProbeResults results;
  const double* parameters[] = {z.data()};
  checker.Probe(parameters, 1e-4, &results);
  REQUIRE(results.return_value);
  // Per column (parameter): the analytic and the numerical Jacobian agree
  // in norm. (Entry by entry, the oscillating sensitivities of the link
  // mode pass through zero, where a relative error means nothing.)
  const auto& analytic = results.jacobians[0];
  const auto& numeric_jacobian = results.numeric_jacobians[0];
  REQUIRE(analytic.cols() == static_cast<Eigen::Index>(scale.size()));
  for (Eigen::Index j = 0; j < analytic.cols(); ++j) {
    const double error = (analytic.col(j) - numeric_jacobian.col(j)).norm() / numeric_jacobian.col(j).norm();
    INFO("parameter " << j << ": |J - J_numeric| / |J_numeric| = " << error);
    CHECK(error < tolerance);
  }
}

}  // namespace

TEST_CASE("step fit, reduced model: analytic Jacobian of the scaled cost matches central differences") {
  CheckGradient(DriveTrainModel::kReduced,
                {DriveTrainParameter::kViscousFriction, DriveTrainParameter::kMotorInertia,
                 DriveTrainParameter::kCoulombFriction},
                true, 1e-6, 1e-4);
}

TEST_CASE("step fit, full model: analytic Jacobian of the scaled cost matches central differences") {
  CheckGradient(DriveTrainModel::kFull,
                {DriveTrainParameter::kViscousFriction, DriveTrainParameter::kMotorInertia,
                 DriveTrainParameter::kGearboxInertia, DriveTrainParameter::kLinkStiffness,
                 DriveTrainParameter::kCoulombFriction},
                false, 1e-3, 2e-3);
}
