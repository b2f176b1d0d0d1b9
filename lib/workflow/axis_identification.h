// The identification of a rigid axis from its logs, as `drivetrain-fit
// axis` runs it (docs/models.md#axis): the method (inverse dynamics or
// output error, `auto` from the logs' torque), the output-error fit's start
// from inverse dynamics, the estimates' units in the logs' units, the
// derived gearbox friction d_g, the feed-forward gains, and the trace and
// plot data. The command parses, loads the logs, calls this, emits.
#pragma once

#include <string>
#include <vector>

#include "core/fit_result.h"
#include "fit/axis/axis_fit.h"
#include "fit/axis/axis_rows.h"
#include "fit/core/least_squares.h"
#include "logs/axis_log.h"
#include "params/parameter_file.h"
#include "models/axis.h"
#include "report/plot.h"

namespace driveid {

enum class AxisMethod { kAuto, kInverseDynamics, kOutputError };

/// The method for these logs: `requested`, or for kAuto output error when
/// every log's torque is held in steps (it changes at < 2 % of the
/// samples), else inverse dynamics; `reason` says why.
AxisMethod ChooseAxisMethod(const std::vector<AxisLog>& logs, AxisMethod requested, std::string* reason);

struct AxisIdentificationOptions {
  AxisMethod method = AxisMethod::kAuto;
  /// The fit's options, passed down as they are: the free set and the
  /// progress callback (axis.fit) for either method, the processing (cutoff,
  /// decimation, torque timing, by default from the data) for inverse
  /// dynamics.
  AxisFitOptions axis = AxisFitOptionsFromData();
  bool trace = false;   ///< build the trace CSV
  bool simulate_rates = false;  ///< build rate_series (for --plot)
  /// The SysId files' position unit when every log is a SysId file in one
  /// unit (estimates, feed-forward in volts and that unit), else "".
  std::string sysid_unit;
  /// The SysId test every log declares ("Simple", "Elevator", "Arm"), else
  /// "": an Arm adds the gravity terms to the default free set.
  std::string sysid_mechanism;
  /// Every bound on these fields (‹field› names the option); see core/option_check.h.
  bool IsValid(std::string* error) const;
};

/// The SysId declarations of the logs (per log: the file's position unit,
/// "" for a log that is no SysId file; its test): the unit when every log
/// is a SysId file in one unit, and then the mechanism when they all
/// declare one, go into `options` (sysid_unit, sysid_mechanism).
void TakeSysIdDeclarations(const std::vector<std::string>& units, const std::vector<std::string>& mechanisms,
                           AxisIdentificationOptions& options);

struct AxisIdentification {
  AxisMethod method = AxisMethod::kInverseDynamics;
  AxisSection section;                  ///< the start section with the estimates put in
  AxisParameters params;
  FitResult fit;                        ///< units in the logs' units; validation of the held-out logs
  std::vector<DerivedQuantity> derived;  ///< d_g with a gear ratio; the relative error of inverse dynamics
  Feedforward feedforward;
  std::string model;                    ///< for the provenance
  std::string trace_csv;                ///< when asked for
  std::vector<PlotSeries> series;       ///< measured and model per log
  PlotLabels labels;
  /// With simulate_rates: per log, the logged rate (qd, else central
  /// differences of q) and the rate the fitted model simulates from the log's
  /// start under its logged effort (SimulateAxisLogRates), what SysId users
  /// compare; a log the simulator cannot follow is left out.
  std::vector<PlotSeries> rate_series;
  std::vector<std::string> summary;     ///< lines for the text summary
};

/// Fits the axis to `logs` from `section` (its `linear` set from SysId
/// logs in a length unit) and predicts `validation` logs (inverse dynamics
/// only: OptionError with output error). Throws as FitAxis and
/// FitAxisOutputError.
AxisIdentification IdentifyAxis(const std::vector<AxisLog>& logs, const AxisSection& section,
                                const AxisIdentificationOptions& options, const std::vector<AxisLog>& validation);

}  // namespace driveid
