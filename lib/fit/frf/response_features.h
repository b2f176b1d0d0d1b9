// Resonance and anti-resonance read from a measured motor-side response
// (docs/models.md#reading-the-resonance), and the band they are read in:
// - band: where the excitation (the input's or the reference's own
//   spectrum) stands within 30 dB of its broadband level (ExcitedBins) and the coherence is at least
//   min_coherence (or the band given); a feature is read only inside it,
//   at least two bins from its edges and below 0.8 of the Nyquist frequency;
// - a peak of |acceleration / torque| that coincides with a line of the
//   excitation's own spectrum (a disturbance the loop passes to the input)
//   or with a harmonic of the mean rotation frequency is flagged and skipped:
//   a disturbance, not a mode;
// - each frequency is refined by a quadratic in w^2 through up to five bins
//   (w^4 = C / A whatever the damping); its std combines the delta method
//   from the bins' own std of ln |H| (coherence, averages) with the spread
//   between the three- and five-bin refinements (the quadratic's model
//   error at the bins' resolution).
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "models/joint.h"
#include "signal/frequency_response.h"

namespace driveid {

/// A measured response: bins with their std (signal/frequency_response.h).
struct ResponseData {
  std::vector<double> frequency;                ///< [Hz]
  std::vector<std::complex<double>> response;
  std::vector<double> coherence;                ///< empty: all taken as coherent
  std::vector<double> log_magnitude_std;        ///< std of ln|H|; empty: 1 (unweighted)
  std::vector<double> phase_std;                ///< [rad]; empty: 1
  std::vector<double> excitation;               ///< the excitation's power per bin; empty: unknown (all excited)
  double nyquist_hz = 0.0;                      ///< 0: unknown (a response measured elsewhere)
  double rotation_hz = 0.0;                     ///< mean rotation frequency of the motor [Hz]; 0: none
};

/// A frequency with its std [Hz].
struct FrequencyEstimate {
  double value = 0.0, standard_error = 0.0;
};

/// Where features are read and fitted: [low, high] given (high > 0), else
/// the excited, coherent band.
struct ResponseBand {
  double low = 0.0, high = 0.0;      ///< [Hz]; 0, 0: from the data
  double min_coherence = 0.5;        ///< bins below leave the band's edges
};

/// Bins in the band whose coherence is at least min(0.2, min_coherence)
/// (a notch lowers it: it stays, weighted by its std) and whose std and
/// response are finite. The band from the data: the first to the last bin
/// with coherence >= min_coherence among the excited bins.
std::vector<char> BandBins(const ResponseData& data, const ResponseBand& band);

/// First and last used frequency [Hz] (0, 0 when none).
void UsedBand(const ResponseData& data, const std::vector<char>& used, double& low, double& high);

struct ResponseFeatures {
  FrequencyEstimate resonance, antiresonance;  ///< 0 when not found
  double band_low = 0.0, band_high = 0.0;      ///< [Hz], band used
  std::vector<std::string> notes;              ///< lines skipped as disturbances, band limits
  std::vector<std::string> warnings;           ///< no resonance in the band
  std::size_t bins = 0;                        ///< usable bins in the band
};

/// Fewest usable bins from which a response is read (or fitted).
inline constexpr std::size_t kMinResponseBins = 5;

/// Reads the largest peak of |acceleration / torque| inside the band and the
/// deepest notch below it (see the file comment).
ResponseFeatures ReadResponseFeatures(const ResponseData& motor, ResponseQuantity quantity, const ResponseBand& band);

}  // namespace driveid
