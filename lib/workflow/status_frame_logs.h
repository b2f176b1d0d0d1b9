// Logs whose position repeats between a device's status frames
// (signal/held_samples.h, docs/models.md#status-frames) re-timed for the
// axis fit: each frame's values once, at the time the frame was measured,
// on one time line with every row's effort.
#pragma once

#include <string>
#include <vector>

#include "core/fit_result.h"
#include "fit/axis/axis_oe_fit.h"
#include "logs/axis_log.h"

namespace driveid {

struct StatusFrameRetiming {
  std::size_t held_logs = 0;    ///< logs whose position is held between frames
  std::size_t held_rates = 0;   ///< logs whose logged rate alone is held (left out)
  std::size_t frames = 0;       ///< frames kept (measured rows)
  std::size_t rows = 0;         ///< rows of the held logs as logged
  double frame_period = 0.0;    ///< the longest median frame period [s]
  double logger_step = 0.0;     ///< the longest median logger step [s]
  std::size_t effort_framed = 0;     ///< logs whose effort comes in frames too
  double effort_frame_period = 0.0;  ///< their longest frame period [s]
};

/// Re-times the logs in place when any of them is held (position or rate
/// in frames, signal/held_samples.h; pooled over the logs), else leaves
/// them alone. Each log's measurements move relative to its rows' effort:
/// - a held position: each frame once, sent between the row before and the
///   row that shows it (-h/2, h the median logger step);
/// - an effort in frames too (period P >= 1.5 h): each value sent before
///   its row and applied about its frame (+h/2 + P/2); else a varying
///   effort centred on its row (+h/2); a step held from its row, or a log
///   that opens at its effort's level (it began with its step), not at all;
/// - `shifts[i]` more for log i (later when positive).
/// Rows between frames keep their effort with `AxisLog::measured` false. A
/// log whose logged rate is held but whose position is not loses its rate
/// (the position, measured at every row, is fitted; `start_rate` keeps its
/// first value).
StatusFrameRetiming RetimeStatusFrames(std::vector<AxisLog>& logs, const std::vector<double>& shifts = {});

/// The measured rows of each log (every row of a log without a mask).
std::vector<AxisLog> MeasuredRows(const std::vector<AxisLog>& logs);

/// The systematic errors of status-frame logs that their residuals cannot
/// show, added to an output-error fit's covariance (AddSystematicCovariance):
/// - each log's timing, with the variance of the moves above (a frame
///   within its step h^2/12; a framed effort (h^2 + P^2)/12; a varying
///   effort h^2/12) and of its stamps' scatter (the steps' robust std,
///   squared); the gradient from fits with that log moved +-h/2;
/// - a quantised effort (its levels multiples of one quantum q) held in
///   steps (fit/axis/axis_oe_fit.h IsTorqueStepLog): the step's level is known to
///   +-q/2 (std q / sqrt(12)); the gradient from fits with that log's effort
///   moved +-q/2 (a ramp crosses many levels: its errors average out).
/// The fits start from `fitted`, without per-log fits. Returns what was
/// added, one line ("" when nothing was); a warning when a fit failed.
std::string AddStatusFrameBudget(const std::vector<AxisLog>& logged, const AxisSection& section,
                                 const AxisParameters& fitted, const AxisOeOptions& options, FitResult& fit);

}  // namespace driveid
