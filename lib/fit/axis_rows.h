// The rows of the axis IDIM-LS (docs/models.md#axis): rates and
// accelerations from the logged position (or a measured rate), the
// full-rate regressor columns [q'', q', sgn q', 1, cos q, sin q, |q'|,
// t - t_mid] and the force through the same parallel-decimation filter,
// every `decimation`-th sample clear of velocity reversals. Shared by the
// fit (axis_fit.h) and the validation of a parameter file (validation.h).
#pragma once

#include <string>
#include <vector>

#include "fit/linear_regression.h"
#include "io/axis_log.h"

namespace driveid {

/// Rates and accelerations at the log's samples (valid: computed there);
/// rate_hz is the constant sampling rate, 0 for irregular sampling.
struct AxisDerivatives {
  std::vector<double> rate, acceleration;
  std::vector<char> valid;
  double rate_hz = 0.0;  // 0 for irregular sampling
};

/// Differentiates the position (or the measured rate) with the position
/// low-pass `cutoff_request` [Hz] (0: rate / 40). OptionError above Nyquist.
AxisDerivatives DifferentiateAxisLog(const AxisLog& log, double cutoff_request);

struct AxisRows {
  LinearRegression regression;  ///< one channel per log ("path:tau")
  std::vector<double> time, measured;
  std::vector<int> log_index;
  std::string method;           ///< how rates were obtained
};

/// Builds the rows over all logs; `column_names` names the eight columns in
/// the order above. InputError for a log shorter than kMinAxisLogSamples.
AxisRows BuildAxisRows(const std::vector<AxisLog>& logs, double cutoff, int decimation, double min_rate_fraction,
                       const std::vector<std::string>& column_names);

}  // namespace driveid
