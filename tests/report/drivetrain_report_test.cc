// report/drivetrain_report.h: eq. (16)'s omega_n and zeta from its own
// coefficients (omega_n = 1 / sqrt(a2), zeta = a1 omega_n / 2), the
// overshoot against a step response integrated here (RK4 of
// y'' + 2 zeta omega_n y' + omega_n^2 y = omega_n^2), the stuck level of the
// paper's step, and the text and JSON carrying the fitted set beside.
#include "report/drivetrain_report.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <catch2/catch.hpp>

#include "params/parameter_file.h"

using namespace driveid;

namespace {

// The largest relative excursion above 1 of a unit step through the second-order lag.
double SimulatedOvershoot(double omega, double zeta) {
  const double h = 1e-3 / omega;
  double y = 0.0, v = 0.0, peak = 0.0;
  const auto acceleration = [&](double yy, double vv) { return omega * omega * (1.0 - yy) - 2.0 * zeta * omega * vv; };
  for (int k = 0; k < 20000; ++k) {
    const double k1y = v, k1v = acceleration(y, v);
    const double k2y = v + 0.5 * h * k1v, k2v = acceleration(y + 0.5 * h * k1y, v + 0.5 * h * k1v);
    const double k3y = v + 0.5 * h * k2v, k3v = acceleration(y + 0.5 * h * k2y, v + 0.5 * h * k2v);
    const double k4y = v + h * k3v, k4v = acceleration(y + h * k3y, v + h * k3v);
    y += h / 6.0 * (k1y + 2.0 * k2y + 2.0 * k3y + k4y);
    v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    peak = std::max(peak, y);
  }
  return peak - 1.0;
}

}  // namespace

TEST_CASE("drive-train report: omega_n, zeta and the overshoot of eq. (16); the fitted set beside") {
  const char* source = std::getenv("DRIVEID_SOURCE_DIR");
  const ParameterFile file = ReadParameterFile(std::string(source ? source : ".") + "/data/paper000.yaml");
  const DriveTrainParameters p = MakeDriveTrainParameters(*file.Find<DriveTrainSection>());
  const DriveTrainQuantities d = CalcDriveTrainQuantities(p);
  CHECK(d.tf.natural_frequency == Approx(1.0 / std::sqrt(d.tf.lag_s2)));
  CHECK(d.tf.damping_ratio == Approx(d.tf.lag_s1 * d.tf.natural_frequency / 2.0));
  REQUIRE(d.tf.damping_ratio < 1.0);
  CHECK(d.overshoot == Approx(SimulatedOvershoot(d.tf.natural_frequency, d.tf.damping_ratio)).epsilon(1e-3));
  // The paper's -0.8 N m motor step through the gear, less the Coulomb friction that holds it.
  const double drive = -0.8 * p.gear_ratio;
  CHECK(d.stuck_level == Approx(drive + std::min(p.coulomb_friction, std::abs(drive))));
  DriveTrainParameters fitted = p;
  fitted.viscous_friction *= 2.0;
  const DriveTrainReport report = CalcDriveTrainReport(p, "paper000.yaml", &fitted, "fit.yaml");
  REQUIRE(report.fitted_quantities.has_value());
  CHECK(report.fitted_quantities->tf.damping_ratio > d.tf.damping_ratio);
  CHECK(FormatDriveTrainReport(report).find("fit.yaml") != std::string::npos);
  CHECK(DriveTrainReportJson(report).contains("fitted"));
}
