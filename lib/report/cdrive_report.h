// Report of a C-drive parameter set (cdrive-fit report): J, J^-1, J'J, the
// inertia matrix M and its isotropy, and a Table-I style table of the
// dissipation parameters beside the paper's, with standard errors when the
// file carries a fit. Computed once as a struct, rendered as text or JSON.
// Documented in docs/models.md#c-drive.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "control/cdrive_control_settings.h"
#include "core/fit_result.h"
#include "models/cdrive.h"
#include "report/json.h"

namespace driveid {

struct CDriveReport {
  /// M of eq. (17), when I_h, I_c and m are all given.
  struct Inertia {
    double a, b;                      ///< diagonal and off-diagonal [kg m^2]
    double collar_inertia;            ///< I_c [kg m^2]
    double isotropic_collar_inertia;  ///< (p / 2 pi)^2 m: the I_c that makes M isotropic (eq. 18)
  };
  /// One dissipation parameter beside Table I.
  struct Dissipation {
    std::string key;
    std::optional<double> value;           ///< not given: nullopt
    std::optional<double> standard_error;  ///< from the file's fit section
    double table_one;                      ///< seed 001 Table I
  };
  std::string source;
  double lead = 0.0;  ///< p [m]
  Matrix2 jacobian, jacobian_inverse;
  double jtj = 0.0;   ///< J'J = p^2 / (8 pi^2) 1 [m^2/rad^2]
  std::optional<Inertia> inertia;
  std::vector<Dissipation> dissipation;  ///< beta, gamma, delta, eta
  std::optional<CDriveControlSettings> control;
};

/// `control` may be null (no controller section).
CDriveReport CalcCDriveReport(const CDriveSection& cdrive, const CDriveControlSection* control,
                              const std::vector<ParameterEstimate>& estimates, const std::string& source);
std::string FormatCDriveReport(const CDriveReport& report);
Json CDriveReportJson(const CDriveReport& report);

}  // namespace driveid
