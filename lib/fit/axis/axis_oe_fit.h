// Output-error identification of a rigid axis (docs/models.md#axis-output-error):
// simulate the axis from the logged torque (held between samples) with
// Coulomb friction that truly sticks (sim/axis_simulator.h), starting at the
// logged position and rate (rate: qd if logged, else the slope of the first
// 10 samples), and fit the free terms to the measured position, and to the
// measured rate where qd is logged, jointly over all logs, through the
// shared fit core (robust covariance, identifiability). The channels are
// weighted by 1 / RMS of their measured deviation from the mean, so that
// position and rate count alike; statistics are reported in their units.
// Start values: `initial` (the caller's IDIM-LS fit of the same terms) or
// the parameter file's values.
#pragma once

#include <string>
#include <vector>

#include "fit/core/least_squares.h"
#include "logs/axis_log.h"
#include "models/axis.h"

namespace driveid {

struct AxisOeOptions {
  std::vector<std::string> free = FitParameterKeys(AxisParameterTable(), "axis", true);
  bool per_log = true;  ///< several logs: each fitted alone too, and tested for agreement
  FitOptions fit;
  /// Every bound on these fields (‹field› names the option); see core/option_check.h.
  bool IsValid(std::string* error) const;
};

struct AxisOeOutput {
  AxisParameters params;
  FitResult fit;
  std::string start_from;  ///< where the start values came from
  /// Simulated position and rate per log, at the log's samples.
  std::vector<std::vector<double>> position, rate;
};

/// Where a simulation of a log starts: the logged position, and the logged
/// rate qd if there is one (or AxisLog::start_rate), else the slope of the
/// first 10 samples.
struct AxisStart {
  double position = 0.0, rate = 0.0;
};
AxisStart AxisLogStart(const AxisLog& log);
/// A logged rate's first value, else the slope over the first 10 samples
/// (0 for a single sample) [position unit / s].
double CalcLoggedStartRate(const std::vector<double>& time, const std::vector<double>& position,
                           const std::vector<double>& rate);

/// Each log simulated with `params` from its logged start (AxisLogStart)
/// under its logged torque, held per sample (sim/axis_simulator.h; no fit):
/// the rate the model predicts for the log, as a simulator would run it. A
/// log the simulator cannot follow (an integrator failure) gets no rates.
std::vector<std::vector<double>> SimulateAxisLogRates(const std::vector<AxisLog>& logs, const AxisParameters& params);

/// Whether a log's torque looks like held steps (it changes at fewer than
/// 2 % of the samples): output error suits it, inverse dynamics does not.
bool IsTorqueStepLog(const AxisLog& log);

/// Fits the free terms; fixed ones from `start` (J, b, tau_c, tau_0 must be
/// given when fixed, the others count as 0; AxisTermsZeroUnlessGiven).
/// `initial` are start values for the free terms (e.g. from IDIM-LS); terms
/// not in it start from `start` or 0. Throws OptionError, InputError,
/// IdentificationError (naming the parameters).
AxisOeOutput FitAxisOutputError(const std::vector<AxisLog>& logs, const AxisSection& start,
                                const AxisParameters* initial, const AxisOeOptions& options);

}  // namespace driveid
