// Nonparametric frequency response from sampled input and output
// (docs/models.md#frequency-response):
// - Welch: Hann-windowed segments with 50 % overlap, linear trend removed per
//   segment; open loop the H1 estimate H = S_uy / S_uu, closed loop with a
//   reference r (the injected excitation or the set-point) H = S_ry / S_ru,
//   which noise fed back through the controller does not bias. Coherence
//   gamma^2 = |S_xy|^2 / (S_xx S_yy); the normalised random error of |H| and
//   the std of its phase [rad] are eps = sqrt(1 - gamma^2) / (|gamma| sqrt(2 n))
//   (Bendat & Piersol), n the number of averages corrected for the overlap;
//   closed loop eps^2 = eps_ry^2 + eps_ru^2 and gamma^2 is reported as the
//   open-loop coherence with that error, 1 / (1 + 2 n eps^2).
// - Periodic: an excitation that repeats with period P (whole periods in the
//   log) is averaged per period (rectangular window, no leakage); H = Y / U of
//   the mean spectra and its error from the spread between periods (the
//   noise variance), only at the excited lines.
#pragma once

#include <complex>
#include <string>
#include <vector>

namespace driveid {

/// One record: equally sampled signals of one log (reference empty when
/// none is given).
struct FrequencyRecord {
  std::vector<double> input, output, reference;
};

enum class FrequencyMethod { kAuto, kWelch, kPeriodic };

struct FrequencyResponseOptions {
  double resolution = 0.0;  ///< Welch bin width [Hz]; 0: about 8 averages over the shortest record, finer
                            ///< (down to 4 averages) to resolve a narrow excited band in 32 bins
  FrequencyMethod method = FrequencyMethod::kAuto;  ///< auto: periodic when the excitation repeats
  double period = 0.0;      ///< [s] periodic method; 0: detected from the excitation
  /// Every bound on these fields (‹field› names the option); see core/option_check.h.
  bool IsValid(std::string* error) const;
};

struct FrequencyResponse {
  std::vector<double> frequency;                 ///< [Hz], DC left out
  std::vector<std::complex<double>> response;    ///< output / input
  std::vector<double> coherence;                 ///< gamma^2 in [0, 1]
  std::vector<double> log_magnitude_std;         ///< std of ln |H| (relative std of |H|); empty: unknown
  std::vector<double> phase_std;                 ///< [rad]; empty: unknown
  /// The stds above are relative only (a measured coherence gives their
  /// ratios, not their scale): they weigh a fit, whose covariance takes the
  /// scale from the residuals, but not a read's delta-method std.
  bool std_scale_unknown = false;
  /// Power of the excitation (the reference closed loop, else the input)
  /// per bin, in its units squared; where it is excited.
  std::vector<double> excitation;
  int averages = 0;     ///< segments (Welch) or periods (periodic), over all records
  double resolution = 0.0;  ///< [Hz]
  bool closed_loop = false;  ///< ratio of cross spectra with the reference
  FrequencyMethod method = FrequencyMethod::kWelch;
  std::string description;  ///< e.g. "Welch H1, Hann, 50 % overlap, 15 averages"
};

/// Estimates the response of `records` sampled at `rate` Hz (pooled: the
/// averages of all records together). Throws OptionError for a resolution or
/// period the records cannot give, InputError for records too short or
/// without excitation.
FrequencyResponse EstimateFrequencyResponse(const std::vector<FrequencyRecord>& records, double rate,
                                            const FrequencyResponseOptions& options);

/// Excitation within this ratio of its broadband level counts as excited (30 dB).
constexpr double kExcitedPowerRatio = 1e-3;

/// Per bin, whether the excitation's power is within kExcitedPowerRatio of
/// its broadband level: the largest running median over 13 bins, so that a
/// single line (a disturbance in the input) does not set it; an isolated
/// line (its running median below that) is not excited either. Empty in, all
/// excited out (of `bins` bins).
std::vector<char> ExcitedBins(const std::vector<double>& excitation, std::size_t bins);

/// The period [samples] with which `signal` repeats, or 0: the first lag
/// whose autocorrelation is a local maximum of at least 0.9 and at which
/// (and at twice which, when three periods fit) the shifted signal differs
/// from itself by at most 0.3 of its rms (a repeating excitation under noise
/// of up to about 20 % of its rms).
std::size_t DetectPeriod(const std::vector<double>& signal);

}  // namespace driveid
