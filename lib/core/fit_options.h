// The options of a least-squares fit (fit/core/least_squares.h solves it): plain
// types every fit and the tools share — the iteration limit, the
// identifiability threshold, the progress callback, the wall-clock limit,
// the large-problem policy and the error clusters.
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "core/option_check.h"

namespace driveid {

/// Progress of one solver iteration (for -v).
struct FitIteration {
  int iteration;
  double cost;
  double gradient_norm;
  double step_norm;
};

/// Seconds on the monotonic clock (for FitOptions::deadline).
inline double MonotonicSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// When a problem counts as large: its Jacobian above `jacobian_bytes`
/// (16 MB). One named policy for the choices that follow from it: a model
/// that evaluates row ranges goes to the solver in chunks of rows and the
/// solver uses the normal equations (least_squares.cc); the memo keeps no
/// Jacobian (scaled_cost.cc); a linear fit is solved exactly on the normal
/// equations (linear_regression.cc); a single long step log is simulated in
/// pieces (step_fit.cc).
struct LargeProblemPolicy {
  std::size_t jacobian_bytes = std::size_t{16} << 20;
  /// Whether a Jacobian of `rows` x `columns` doubles is large.
  bool IsLarge(std::size_t rows, std::size_t columns) const {
    return rows * columns * sizeof(double) > jacobian_bytes;
  }
};

/// Rows [begin, begin + count) of a problem's residuals.
struct RowRange {
  int begin = 0;
  int count = 0;
};

struct FitOptions {
  int max_iterations = 100;
  /// Smallest singular value of the column-normalised Jacobian below which
  /// the parameters count as not identifiable (collinearity index 1/s > 1000).
  double identifiability_threshold = 1e-3;
  /// Optional advice for a non-identifiable set, given the parameters involved.
  std::function<std::string(const std::vector<std::string>&)> advice;
  std::function<void(const FitIteration&)> progress;
  /// Wall-clock limit of one solver run [s] (0: none). Reached, the run ends
  /// at its best point so far with a warning instead of a refusal.
  double max_seconds = 0.0;
  /// The whole command's limit on MonotonicSeconds() (0: none): every solver
  /// run gets at most the time left, and a run that would start after it is
  /// refused naming the limit (`max_seconds` says how long it was).
  double deadline = 0.0;
  /// Told true when a solver run starts and false when it ends (also by an
  /// exception): a caller's heartbeat speaks only while a fit runs.
  std::function<void(bool)> running;
  LargeProblemPolicy large;
  /// Groups of rows whose errors may be correlated in any way among
  /// themselves (across channels too) and are independent between groups,
  /// e.g. a multiple-shooting segment's rows in every channel. Given, the
  /// covariance is cluster-robust over them and the interval's quantile is
  /// Student's t with G - 1 degrees of freedom (docs/models.md#identification).
  std::vector<std::vector<RowRange>> clusters;
  /// Solve each step on the normal equations (P x P) rather than a QR of
  /// the N x P Jacobian: for wide problems (a multiple-shooting fit's
  /// segment states), where the QR's Householder updates dominate; the
  /// parameters are scaled and identifiable, so squaring the condition
  /// number costs no accuracy that matters (as for large problems).
  bool normal_equations = false;
  /// Every bound on these fields (‹field› names the option); see core/option_check.h.
  bool IsValid(std::string* error) const {
    return OptionCheck(error)
        .Require(max_iterations >= 1, "max_iterations", max_iterations, ">= 1")
        .Require(identifiability_threshold >= 0.0 && identifiability_threshold < 1.0, "identifiability_threshold",
                 identifiability_threshold, "0 <= threshold < 1")
        .Require(NotNegative(max_seconds), "‹max_seconds›", max_seconds, "max seconds >= 0 (0: no limit)");
  }
};

}  // namespace driveid
