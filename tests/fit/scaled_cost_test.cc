// Ceres GradientChecker on the scaled cost of the step fit: the analytic
// Jacobian (CVODES forward sensitivities with jump conditions at stick/slip
// events, times the parameter scales) against Ceres's central differences,
// for the reduced and the full model, away from the truth so that the
// residuals are large and every term matters. The full model integrates the
// undamped link mode throughout, so its differences need a step well above
// the integrator's tolerance (1e-7 relative), as in drivetrain_simulator_test.
#include "fit/core/scaled_cost.h"

#include <cmath>
#include <random>

#include <ceres/gradient_checker.h>
#include <ceres/numeric_diff_options.h>

#include <catch2/catch.hpp>

#include "fit/step/step_fit.h"
#include "sim/drivetrain_simulator.h"
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

namespace {

// r_i = p0 + p1 t_i - y_i, counting its evaluations.
class CountingLine final : public ResidualModel {
 public:
  int residual_count() const override { return 3; }
  bool Evaluate(const double* p, double* r, double* jacobian) override {
    ++calls;
    if (jacobian != nullptr) ++jacobian_calls;
    for (int i = 0; i < 3; ++i) {
      r[i] = p[0] + p[1] * i - 2.0 * i;
      if (jacobian != nullptr) {
        jacobian[2 * i] = 1.0;
        jacobian[2 * i + 1] = i;
      }
    }
    return true;
  }
  int calls = 0, jacobian_calls = 0;
};

}  // namespace

TEST_CASE("scaled cost: one model evaluation per point, whatever Ceres asks of it again") {
  CountingLine line;
  ScaledCost cost(line, {2.0, 4.0});
  double z[] = {0.5, 0.25};
  const double* parameters[] = {z};
  double r1[3], r2[3], j1[6], j2[6];
  double* jacobians1[] = {j1};
  double* jacobians2[] = {j2};
  REQUIRE(cost.Evaluate(parameters, r1, jacobians1));
  REQUIRE(cost.Evaluate(parameters, r2, nullptr));     // its cost again
  REQUIRE(cost.Evaluate(parameters, r2, jacobians2));  // its Jacobian again
  CHECK(line.calls == 1);
  CHECK(cost.model_evaluations() == 1);
  for (int i = 0; i < 3; ++i) CHECK(r2[i] == r1[i]);
  for (int i = 0; i < 6; ++i) CHECK(j2[i] == j1[i]);
  CHECK(j1[1] == 0.0);
  CHECK(j1[3] == 4.0);  // dr/dz = dr/dp * scale

  // Residuals first, then the Jacobian at that point: the model must be
  // evaluated again (the memo held no Jacobian).
  z[0] = 0.75;
  REQUIRE(cost.Evaluate(parameters, r1, nullptr));
  REQUIRE(cost.Evaluate(parameters, r2, jacobians2));
  CHECK(line.calls == 3);
  CHECK(line.jacobian_calls == 2);
  CHECK(r1[0] == 1.5);
  // A point differing in the last bit is another point.
  z[0] = std::nextafter(0.75, 1.0);
  REQUIRE(cost.Evaluate(parameters, r1, nullptr));
  CHECK(line.calls == 4);
}

TEST_CASE("a long single log is simulated in pieces: any rows, any order, equal to one whole simulation") {
  // 600 000 samples x (3 + offset) columns: a large Jacobian (LargeProblemPolicy).
  const std::size_t n = 600000;
  static_assert(600000 * 4 * sizeof(double) > LargeProblemPolicy{}.jacobian_bytes);
  StepLog log{"long.csv", {}, {}, {}, {}, {}};
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.1);
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) * 1e-6;
    log.time.push_back(t);
    log.motor_torque.push_back(t < 0.01 ? 0.0 : (t < 0.3 ? -0.8 : 0.4));
    log.link_torque.push_back(noise(rng));
  }
  const std::vector<StepLog> logs = {log};
  const DriveTrainParameters params = testing_support::PaperDriveTrain();
  const std::vector<DriveTrainParameter> free{DriveTrainParameter::kViscousFriction, DriveTrainParameter::kMotorInertia,
                                              DriveTrainParameter::kCoulombFriction};
  const double offset = 0.7;
  const std::vector<double> point{params.viscous_friction, params.motor_inertia, params.coulomb_friction, offset};
  // Expected: one whole simulation.
  DriveTrainSimulator simulator(DriveTrainModel::kReduced, params, free);
  DriveTrainResponse whole;
  simulator.Simulate(params, log.time, log.motor_torque, true, &whole);
  REQUIRE(whole.switch_count >= 2);
  auto model = MakeStepResiduals(logs, params, DriveTrainModel::kReduced, free, true);
  REQUIRE(model->evaluates_rows());
  const auto check = [&](int begin, int end, bool with_jacobian) {
    std::vector<double> r(static_cast<std::size_t>(end - begin)), j(with_jacobian ? r.size() * 4 : 0);
    REQUIRE(model->EvaluateRows(point.data(), begin, end, r.data(), with_jacobian ? j.data() : nullptr));
    int wrong = 0;
    for (int row = begin; row < end; ++row) {
      const std::size_t k = static_cast<std::size_t>(row), i = static_cast<std::size_t>(row - begin);
      wrong += r[i] != whole.link_torque[k] + offset - log.link_torque[k];
      for (std::size_t c = 0; with_jacobian && c < 4; ++c) {
        wrong += j[i * 4 + c] != (c < 3 ? whole.link_torque_sensitivity[k * 3 + c] : 1.0);
      }
    }
    INFO("rows " << begin << " .. " << end << (with_jacobian ? " with" : " without") << " Jacobian");
    CHECK(wrong == 0);
  };
  check(0, 8192, true);            // a sweep begins
  check(8192, 20000, true);        // goes on
  check(450000, 450100, true);     // rows ahead: simulated up to them
  check(100, 200, true);           // rows behind: simulated again
  check(0, 600000, false);         // residuals of a whole sweep
  check(300000, 300500, false);    // residuals remembered
  std::vector<double> r(n), j(n * 4);
  REQUIRE(model->Evaluate(point.data(), r.data(), j.data()));  // the whole model, in pieces
  CHECK(r[599999] == whole.link_torque[599999] + offset - log.link_torque[599999]);
  CHECK(j[599999 * 4 + 2] == whole.link_torque_sensitivity[599999 * 3 + 2]);
}
