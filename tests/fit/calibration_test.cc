// Monte-Carlo calibration of the reported standard errors (ctest label
// `slow`): over many independent noise realisations from the independent
// reference generators, the empirical standard deviation of each estimate
// must match the mean reported standard error from both sides (ratio within
// 0.85-1.15) and the 95 % intervals must cover the truth about 95 % of the
// time. With 400 seeds the ratio itself scatters by about 3.5 % (1 / sqrt(2 N)),
// so the band is over four of its standard deviations wide on each side.
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "fit/axis_fit.h"
#include "fit/step_fit.h"
#include "support/paper000.h"
#include "support/reference_drivetrain.h"

using namespace driveid;

namespace {

// Estimates of one parameter over the seeds.
struct Sample {
  std::vector<double> value, reported_std;
  int covered = 0;

  void Add(const ParameterEstimate& e, double truth) {
    value.push_back(e.value);
    reported_std.push_back(e.standard_error);
    covered += e.ci95_low <= truth && truth <= e.ci95_high;
  }
  double Ratio() const {  // empirical std / mean reported std
    const double n = static_cast<double>(value.size());
    double mean = 0.0, reported = 0.0;
    for (double v : value) mean += v / n;
    double variance = 0.0;
    for (double v : value) variance += (v - mean) * (v - mean) / (n - 1.0);
    for (double s : reported_std) reported += s / n;
    return std::sqrt(variance) / reported;
  }
  double Coverage() const { return static_cast<double>(covered) / static_cast<double>(value.size()); }
};

const ParameterEstimate& Find(const FitResult& fit, const std::string& name) {
  for (const auto& e : fit.estimates) {
    if (e.name == name) return e;
  }
  throw std::logic_error("no estimate " + name);
}

void CheckCalibrated(const std::string& name, const Sample& sample) {
  INFO(name << ": empirical / reported std = " << sample.Ratio() << ", 95 % coverage " << sample.Coverage());
  CHECK(sample.Ratio() > 0.85);
  CHECK(sample.Ratio() < 1.15);
  CHECK(sample.Coverage() >= 0.91);
  CHECK(sample.Coverage() <= 0.99);
}

}  // namespace

TEST_CASE("step fit, reduced model, white strain-gauge noise: reported std calibrated over 400 seeds") {
  const reference::DriveTrain truth;
  const double true_inertia = truth.J / (truth.n_g * truth.n_g);
  DriveTrainParameters start = testing_support::PaperDriveTrain();
  start.motor_inertia = true_inertia * 2.5;
  start.viscous_friction = truth.d_g / 3.0;
  start.coulomb_friction = truth.tau_c * 2.0;
  Sample viscous, inertia, coulomb;
  for (unsigned seed = 1000; seed < 1400; ++seed) {
    const auto log = reference::SimulateStep(truth, 1000.0, 0.2, 0.02, -0.8, 0.1, 0.0, seed);
    const auto out = FitStepResponses({{"mc.csv", log.t, log.tau_motor, log.tau_link}}, start, {});
    viscous.Add(Find(out.fit, "d_g"), truth.d_g);
    inertia.Add(Find(out.fit, "Theta_motor"), true_inertia);
    coulomb.Add(Find(out.fit, "tau_c"), truth.tau_c);
  }
  CheckCalibrated("d_g", viscous);
  CheckCalibrated("Theta_motor", inertia);
  CheckCalibrated("tau_c", coulomb);
}
