// `drivetrain-fit frf` as one library call (docs/models.md#frequency-response):
// logs of torque, a motor-side output (and optionally a link signal and the
// injected reference) become a nonparametric frequency response, the
// resonance and anti-resonance read from it and, if asked, the two-mass
// joint fitted to it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "fit/frf/frequency_response_fit.h"
#include "models/frequency_response.h"
#include "signal/frequency_response.h"

namespace driveid {

/// One log's signals (time [s]; reference and link empty when not logged).
struct FrfSignals {
  std::string label;
  std::vector<double> time, input, output, reference, link;
};

struct FrfOptions {
  FrequencyResponseOptions estimate;
  bool fit = false;                 ///< --fit two-mass
  bool hold = true;                 ///< the torque is held between samples (zero-order hold)
  TwoMassFitOptions two_mass;       ///< outputs' quantities, band, free set
  /// Every bound on these fields (‹field› names the option); see core/option_check.h.
  bool IsValid(std::string* error) const;
};

struct FrfResult {
  double rate = 0.0;  ///< [Hz]
  FrequencyResponse motor;
  std::optional<FrequencyResponse> link;
  ResponseFeatures read;
  std::optional<TwoMassFitOutput> fit;
  std::vector<std::string> notes;     ///< resampling, method
  std::vector<std::string> warnings;  ///< e.g. closed loop without a reference
  /// The `frf` section of the parameter file.
  FrequencyResponseSection Section() const;
};

/// Throws InputError (logs unusable: too short, rates differ, not finite),
/// OptionError (resolution, period), IdentificationError (the fit).
FrfResult AnalyseFrequencyResponse(const std::vector<FrfSignals>& logs, const JointSection& start,
                                   const FrfOptions& options);

/// A response measured elsewhere (`frf --measured`): frequency [Hz],
/// magnitude (linear), phase [rad] and optionally coherence; without a std
/// every bin weighs the same (the fit estimates the residual scale).
struct MeasuredResponse {
  std::vector<double> frequency, magnitude, phase, coherence;
};
/// Features and (options.fit) the two-mass fit of a measured response; the
/// model is continuous (no hold: the sampling is unknown).
FrfResult AnalyseMeasuredResponse(const MeasuredResponse& measured, const JointSection& start, const FrfOptions& options);

}  // namespace driveid
