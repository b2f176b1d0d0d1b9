// Validation (docs/models.md#validation): logs predicted from parameters,
// against logs from generators written independently of the library.
#include "fit/validation/validation.h"

#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include "fit/axis/axis_fit.h"
#include "support/paper000.h"
#include "support/reference_drivetrain.h"

using namespace driveid;

namespace {

// A two-sine axis log (own generator): tau = J q'' + b q' + tau_c sgn q' +
// tau_0 + white noise `sigma`, 1 kHz for 20 s.
AxisLog TwoSineLog(double sigma, unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  AxisLog log;
  log.path = "two_sine.csv";
  for (int k = 0; k <= 20000; ++k) {
    const double t = k / 1000.0, w1 = 2 * M_PI * 0.4, w2 = 2 * M_PI * 1.3;
    const double q = 0.8 * std::sin(w1 * t) + 0.3 * std::sin(w2 * t + 0.5);
    const double qd = 0.8 * w1 * std::cos(w1 * t) + 0.3 * w2 * std::cos(w2 * t + 0.5);
    const double qdd = -0.8 * w1 * w1 * std::sin(w1 * t) - 0.3 * w2 * w2 * std::sin(w2 * t + 0.5);
    log.time.push_back(t);
    log.position.push_back(q);
    log.force.push_back(0.05 * qdd + 0.2 * qd + 0.3 * ((qd > 0) - (qd < 0)) + 0.1 + noise(random));
  }
  return log;
}

}  // namespace

TEST_CASE("validate axis: the true parameters predict a held-out log to the noise; wrong ones do not") {
  const AxisLog log = TwoSineLog(0.02, 21);
  const AxisParameters truth{0.05, 0.2, 0.3, 0.1};
  const auto good = ValidateAxis({log}, truth, 15.0, 10);
  REQUIRE(good.size() == 1);
  // The decimation filter keeps ~0.8 / 10 of the white noise's band.
  CHECK(good[0].stats.rmse == Approx(0.02 * std::sqrt(0.08)).epsilon(0.25));
  CHECK(good[0].stats.fit_percent > 95.0);
  CHECK(good[0].stats.samples == static_cast<int>(good[0].model.size()));
  AxisParameters wrong = truth;
  wrong.viscous = 0.4;
  const auto bad = ValidateAxis({log}, wrong, 15.0, 10);
  CHECK(bad[0].stats.fit_percent < good[0].stats.fit_percent - 20.0);
  CHECK(ChooseAxisValidationCutoff({log}, truth, 10) > 0.0);
}

TEST_CASE("validate axis: on the fitted log it reproduces the fit's own fit % and RMSE") {
  const AxisLog log = TwoSineLog(0.05, 22);
  const AxisFitOutput fit = FitAxis({log}, AxisSection{}, {});
  const auto v = ValidateAxis({log}, fit.params, fit.cutoff, 10);
  REQUIRE(fit.fit.channels.size() == 1);
  CHECK(v[0].stats.fit_percent == Approx(fit.fit.channels[0].fit_percent).epsilon(1e-9));
  CHECK(v[0].stats.rmse == Approx(fit.fit.channels[0].rmse).epsilon(1e-9));
}

TEST_CASE("validate step: the reference drive train's log is simulated from its motor torque to the noise") {
  const reference::DriveTrain truth;
  const auto ref = reference::SimulateStep(truth, 1000.0, 0.2, 0.02, -0.8, 0.1, 0.0, 31);
  DriveTrainParameters params = testing_support::PaperDriveTrain();
  params.motor_inertia = truth.J / (truth.n_g * truth.n_g);
  params.viscous_friction = truth.d_g;
  params.coulomb_friction = truth.tau_c;
  const auto v = ValidateSteps({{"ref.csv", ref.t, ref.tau_motor, ref.tau_link, {}, {}}}, params, DriveTrainModel::kReduced);
  REQUIRE(v.size() == 1);
  CHECK(v[0].stats.rmse == Approx(0.1).epsilon(0.15));
  CHECK(v[0].stats.name == "ref.csv:tau_link");
  DriveTrainParameters wrong = params;
  wrong.coulomb_friction = 2.0 * truth.tau_c;
  CHECK(ValidateSteps({{"ref.csv", ref.t, ref.tau_motor, ref.tau_link, {}, {}}}, wrong, DriveTrainModel::kReduced)[0]
            .stats.rmse > 0.3);
}
