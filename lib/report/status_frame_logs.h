// Logs whose position repeats between a device's status frames
// (signal/held_samples.h, docs/models.md#status-frames) re-timed for the
// axis fit: each frame's values once, at the time the frame was measured,
// on one time line with every row's effort.
#pragma once

#include <string>
#include <vector>

#include "core/fit_result.h"
#include "fit/axis_oe_fit.h"
#include "io/axis_log.h"

namespace driveid {

struct StatusFrameRetiming {
  std::size_t held_logs = 0;    ///< logs whose position is held between frames
  std::size_t held_rates = 0;   ///< logs whose logged rate alone is held (left out)
  std::size_t frames = 0;       ///< frames kept (measured rows)
  std::size_t rows = 0;         ///< rows of the held logs as logged
  double frame_period = 0.0;    ///< the longest median frame period [s]
  double logger_step = 0.0;     ///< the longest median logger step [s]
};

/// Re-times the held logs in place: a frame first seen at row k was sent
/// between rows k-1 and k, and is placed half a logger step before row k,
/// shifted by `shifts[i]` [s] for log i (later when positive; none when
/// `shifts` is empty); rows between frames keep their effort with
/// `AxisLog::measured` false. A log whose logged rate is held but whose
/// position is not loses its rate (the position, measured at every row, is
/// fitted). Logs that are not held are left as they are.
StatusFrameRetiming RetimeStatusFrames(std::vector<AxisLog>& logs, const std::vector<double>& shifts = {});

/// The measured rows of each log (every row of a log without a mask).
std::vector<AxisLog> MeasuredRows(const std::vector<AxisLog>& logs);

/// The systematic errors of status-frame logs that their residuals cannot
/// show, added to an output-error fit's covariance (AddSystematicCovariance):
/// - each held log's timing: a frame is placed half a logger step h before
///   the row that shows it, and the effort's hold within its row is as
///   uncertain, two uniform errors of width h (std h / sqrt(6)); the
///   gradient from fits of `logged` with that log's frames shifted +-h/2;
/// - a quantised effort (its levels multiples of one quantum q) held in
///   steps (fit/axis_oe_fit.h IsTorqueStepLog): the step's level is known to
///   +-q/2 (std q / sqrt(12)); the gradient from fits with that log's effort
///   moved +-q/2 (a ramp crosses many levels: its errors average out).
/// The fits start from `fitted`, without per-log fits. Returns what was
/// added, one line ("" when nothing was).
std::string AddStatusFrameBudget(const std::vector<AxisLog>& logged, const AxisSection& section,
                                 const AxisParameters& fitted, const AxisOeOptions& options, FitResult& fit);

}  // namespace driveid
