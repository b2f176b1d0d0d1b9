// The two-mass joint (docs/models.md#elastic-joint) fitted to a measured
// frequency response (docs/models.md#frequency-response): residuals are
// ln(G_model / H) per bin, its real part (log magnitude) and its imaginary
// part (phase, wrapped) each divided by the bin's std, over the coherent
// band; the shared fit core gives the robust covariance and the
// identifiability analysis. A response of the link (torque -> link angle)
// is fitted jointly when given. Resonance and anti-resonance follow from
// the estimates with their std by the delta method.
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "fit/core/least_squares.h"
#include "fit/frf/response_features.h"
#include "models/joint.h"

namespace driveid {

struct TwoMassFitOptions {
  /// Free: any of motor_inertia, link_inertia, stiffness, damping,
  /// motor_viscous, link_viscous, and `delay` (a pure input delay [s]).
  std::vector<std::string> free = TwoMassDefaultFree();
  ResponseQuantity motor_output = ResponseQuantity::kRate;
  ResponseQuantity link_output = ResponseQuantity::kPosition;
  double band_low = 0.0, band_high = 0.0;  ///< [Hz]; 0, 0: the coherent bins
  double min_coherence = 0.5;              ///< bins below are left out
  /// Sampling with the torque held between samples (zero-order hold) at
  /// this rate [Hz]: the model is the exactly sampled system
  /// (models/joint.h SampledJointResponse). 0: the continuous response.
  double hold_rate = 0.0;
  FitOptions fit;
  ResponseBand Band() const { return {band_low, band_high, min_coherence}; }
  /// Every bound on these fields (‹field› names the option); see core/option_check.h.
  bool IsValid(std::string* error) const;
};

struct TwoMassFitOutput {
  JointParameters params;
  double delay = 0.0;  ///< [s]
  FitResult fit;
  ResponseFeatures read;  ///< from the data (the start)
  FrequencyEstimate resonance, antiresonance;  ///< from the estimates [Hz]
  double band_low = 0.0, band_high = 0.0;      ///< [Hz]
  /// The model at every bin of the motor (and link) data.
  std::vector<std::complex<double>> motor_model, link_model;
  std::vector<char> motor_used, link_used;  ///< bins in the fit
};

/// Fits the free parameters; fixed ones from `start` (0 when absent),
/// gear_ratio 1 when absent. `link` may be null. Throws OptionError for an
/// unknown free name, InputError for data without coherent bins,
/// IdentificationError when not identifiable or the resonance or
/// anti-resonance lies outside the coherent band.
TwoMassFitOutput FitTwoMassResponse(const ResponseData& motor, const ResponseData* link, const JointSection& start,
                                    const TwoMassFitOptions& options);

}  // namespace driveid
