// report/cdrive_report.h: J times J^-1 is the identity, J'J = p^2 / (8 pi^2) 1
// (the paper's orthogonality), the isotropic collar inertia (p / 2 pi)^2 m
// makes the inertia matrix M = [a b; b a] (eq. 17) diagonal, and the fit's
// standard errors stand beside Table I.
#include "report/cdrive_report.h"

#include <cmath>
#include <cstdlib>

#include <catch2/catch.hpp>

#include "params/parameter_file.h"

using namespace driveid;

TEST_CASE("C-drive report: J and its inverse, J'J, the isotropic collar inertia, standard errors by key") {
  const char* source = std::getenv("DRIVEID_SOURCE_DIR");
  const ParameterFile file = ReadParameterFile(std::string(source ? source : ".") + "/data/cdrive_table1.yaml");
  CDriveSection section = *file.Find<CDriveSection>();
  const CDriveReport report = CalcCDriveReport(section, nullptr, {{"beta", 0.0027, 1e-5, 0.0, 0.0, ""}}, "t.yaml");
  const double p = report.lead;
  const Matrix2 identity = report.jacobian * report.jacobian_inverse;
  CHECK(identity(0, 0) == Approx(1.0));
  CHECK(identity(1, 1) == Approx(1.0));
  CHECK(identity(0, 1) == Approx(0.0).margin(1e-12));
  CHECK(identity(1, 0) == Approx(0.0).margin(1e-12));
  const Matrix2 jtj = report.jacobian.transpose() * report.jacobian;
  CHECK(jtj(0, 0) == Approx(p * p / (8.0 * M_PI * M_PI)));
  CHECK(jtj(0, 1) == Approx(0.0).margin(1e-15));
  CHECK(report.jtj == Approx(p * p / (8.0 * M_PI * M_PI)));
  REQUIRE(report.inertia.has_value());
  const double isotropic = report.inertia->isotropic_collar_inertia;
  CHECK(isotropic == Approx(std::pow(p / (2.0 * M_PI), 2) * section.collar_mass.value_or(0.0)));
  section.collar_inertia = isotropic;
  const CDriveReport at = CalcCDriveReport(section, nullptr, {}, "t.yaml");
  CHECK(at.inertia->b == Approx(0.0).margin(1e-12 * std::abs(at.inertia->a)));
  REQUIRE(report.dissipation.size() == 4);
  CHECK(report.dissipation[0].key == "beta");
  CHECK(report.dissipation[0].standard_error.value_or(0.0) == 1e-5);
  CHECK_FALSE(report.dissipation[1].standard_error.has_value());
  CHECK(FormatCDriveReport(report).find("t.yaml") != std::string::npos);
  CHECK(CDriveReportJson(report).is_object());
}
