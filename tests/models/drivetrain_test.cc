// Checks of the drive-train model derivatives against finite differences and
// of eq. (16) against the closed form with the paper's values.
#include "models/drivetrain.h"

#include <cmath>

#include <catch2/catch.hpp>

#include "support/paper000.h"

using namespace driveid;

namespace {
using testing_support::PaperDriveTrain;

const DriveTrainParameter kAll[] = {
    DriveTrainParameter::kViscousFriction, DriveTrainParameter::kMotorInertia,
    DriveTrainParameter::kGearboxInertia,  DriveTrainParameter::kLinkStiffness,
    DriveTrainParameter::kGearboxStiffness, DriveTrainParameter::kCoulombFriction};
}  // namespace

TEST_CASE("state and parameter Jacobians match central differences") {
  const auto params = PaperDriveTrain();
  const double state[4] = {-6e-3, -0.4, -3.5e-3, 0.7};
  const double torque = -0.8;
  for (auto model : {DriveTrainModel::kReduced, DriveTrainModel::kFull}) {
    const int n = DriveTrainStateSize(model);
    for (int mode : {-1, 0, 1}) {
      double jacobian[16];
      CalcDriveTrainStateJacobian(params, model, mode, jacobian);
      for (int col = 0; col < n; ++col) {
        double plus[4], minus[4], xp[4], xm[4];
        std::copy(state, state + 4, xp);
        std::copy(state, state + 4, xm);
        const double h = 1e-6 * std::max(1e-3, std::abs(state[col]));
        xp[col] += h;
        xm[col] -= h;
        CalcDriveTrainDerivatives(params, model, torque, mode, xp, plus);
        CalcDriveTrainDerivatives(params, model, torque, mode, xm, minus);
        for (int row = 0; row < n; ++row) {
          const double fd = (plus[row] - minus[row]) / (2 * h);
          CHECK(jacobian[col * n + row] == Approx(fd).margin(1e-6 * (1 + std::abs(fd))));
        }
      }
      for (auto parameter : kAll) {
        double column[4];
        CalcDriveTrainParameterJacobian(params, model, torque, mode, state, parameter, column);
        const double value = GetDriveTrainParameter(params, parameter);
        const double h = 1e-6 * value;
        auto pp = params, pm = params;
        SetDriveTrainParameter(pp, parameter, value + h);
        SetDriveTrainParameter(pm, parameter, value - h);
        double plus[4], minus[4];
        CalcDriveTrainDerivatives(pp, model, torque, mode, state, plus);
        CalcDriveTrainDerivatives(pm, model, torque, mode, state, minus);
        for (int row = 0; row < n; ++row) {
          const double fd = (plus[row] - minus[row]) / (2 * h);
          INFO("parameter " << DriveTrainParameterKey(parameter) << " row " << row << " mode " << mode);
          CHECK(column[row] == Approx(fd).epsilon(1e-5).margin(1e-9 * (1 + std::abs(fd))));
        }
        const double output = CalcLinkTorqueParameterDerivative(params, model, state, parameter);
        const double output_fd =
            (CalcLinkTorque(pp, model, state) - CalcLinkTorque(pm, model, state)) / (2 * h);
        CHECK(output == Approx(output_fd).epsilon(1e-6).margin(1e-12));
      }
    }
  }
}

TEST_CASE("reduced model equals the full model's static limit") {
  // With Theta_g = 0 the deflection follows phi statically: at equilibrium
  // of (14) Delta = k_Tg phi/(k_Tl + k_Tg), so both give the same link torque.
  const auto params = PaperDriveTrain();
  const double phi = 1e-3;
  const double delta = params.gearbox_stiffness * phi / (params.link_stiffness + params.gearbox_stiffness);
  const double full_state[4] = {phi, 0, delta, 0};
  const double reduced_state[2] = {phi, 0};
  CHECK(CalcLinkTorque(params, DriveTrainModel::kFull, full_state) ==
        Approx(CalcLinkTorque(params, DriveTrainModel::kReduced, reduced_state)));
  CHECK(CalcNetTorque(params, DriveTrainModel::kFull, 0.5, full_state) ==
        Approx(CalcNetTorque(params, DriveTrainModel::kReduced, 0.5, reduced_state)));
}

TEST_CASE("eq. (16) with the paper's values: omega_n, zeta, gain") {
  const auto tf = CalcReducedTransferFunction(PaperDriveTrain());
  const double k_eq = 15000.0 * 18375.0 / (15000.0 + 18375.0);
  CHECK(tf.gain == 80.0);
  CHECK(tf.lag_s2 == Approx(0.413 / k_eq));
  CHECK(tf.lag_s1 == Approx(6400 * 0.016 / k_eq));
  CHECK(tf.natural_frequency == Approx(std::sqrt(k_eq / 0.413)));
  CHECK(tf.natural_frequency > 138.0);
  CHECK(tf.natural_frequency < 142.0);
  CHECK(tf.damping_ratio > 0.86);
  CHECK(tf.damping_ratio < 0.9);
  CHECK(tf.lag_s1 == Approx(0.0124).epsilon(0.01));  // the 0.013 s of eq. (17), not its misprinted 0.031 s
}
