// The C-drive's fits as `cdrive-fit friction` and `cdrive-fit inertia` run
// them (docs/models.md#c-drive): the fit of all logs, eq. (31)'s friction
// compensation with the fit's uncertainty (friction), the trace of measured
// and model motor torques and its plot. The command parses, loads the logs,
// calls this, emits.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/fit_result.h"
#include "fit/cdrive/cdrive_fit.h"
#include "logs/cdrive_log.h"
#include "params/parameter_file.h"
#include "models/feedforward.h"
#include "report/plot.h"

namespace driveid {

enum class CDriveFitKind { kFriction, kInertia };

/// The differentiator's half window a kind takes by default [s]: 0.01 for
/// the slow friction programs, 0.005 for the fast inertia programs.
double CDriveDefaultHalfWindow(CDriveFitKind kind);

struct CDriveIdentificationOptions {
  CDriveFitKind kind = CDriveFitKind::kFriction;
  CDriveFitOptions fit;  ///< its traces are asked for when a trace or plot is
  bool trace = false;    ///< build the trace CSV's rows
  bool plot = false;     ///< build the plot panels
  /// Every bound on these fields (‹field› names the option); see core/option_check.h.
  bool IsValid(std::string* error) const;
};

struct CDriveIdentification {
  CDriveSection section;                 ///< the start values with the estimates put in
  FitResult fit;
  std::vector<DerivedQuantity> derived;  ///< a and b of eq. (17) for the inertia fit
  std::optional<Feedforward> feedforward;  ///< eq. (31) as a controller loads it (friction)
  std::string model;                     ///< for the provenance
  std::string trace_csv;
  std::vector<PlotPanel> panels;         ///< one per log, then the residuals of the samples used
};

/// Fits `logs` from the file's cdrive section (InputError naming `path`
/// without one); its cdrive_control section, or the seed's settings, for
/// the compensation. Throws as FitCDriveFriction / FitCDriveInertia.
CDriveIdentification IdentifyCDrive(const std::vector<CDriveLog>& logs, const ParameterFile& start,
                                    const std::string& path, const CDriveIdentificationOptions& options);

}  // namespace driveid
