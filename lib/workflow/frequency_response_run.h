// `drivetrain-fit frf` around its one library call (fit/frf/frf_analysis.h):
// the names of the response's quantities, a measured response brought to
// Hz, linear magnitude and radians, a log's columns made the analysis'
// signals, and the parameter file the run writes
// (docs/models.md#frequency-response).
#pragma once

#include <string>
#include <vector>

#include "fit/frf/frf_analysis.h"
#include "logs/csv_log.h"
#include "params/parameter_file.h"
#include "report/plot.h"

namespace driveid {

/// The quantity a name spells: position, rate, acceleration (the choices of
/// --output-is and --link-is); OptionError naming `option` for another.
ResponseQuantity ResponseQuantityFromName(const std::string& name, const std::string& option);
/// What a logged signal is from its name: q_* a position, qd_* a rate; ""
/// when the name does not say.
std::string ResponseQuantityOfSignal(const std::string& expression);

/// The units a response measured elsewhere comes in (`frf --measured`).
struct MeasuredResponseUnits {
  bool radians_per_second = false;  ///< frequency in rad/s (else Hz)
  bool decibel = false;             ///< magnitude 20 log10 |G| (else |G|)
  bool degrees = true;              ///< phase in degrees (else radians)
};
/// `measured` in Hz, linear magnitude and radians.
MeasuredResponse MeasuredResponseInSi(MeasuredResponse measured, const MeasuredResponseUnits& units);

/// A log read with the columns t, tau|i, the output, then (when logged) the
/// reference and the link signal, as the analysis' signals: a current i is
/// made a torque with `torque_constant` (InputError naming the log without
/// one > 0).
FrfSignals FrfSignalsFromLog(CsvLog log, double torque_constant, bool has_reference, bool has_link);

/// The parameter file `frf` writes: `start` with the `frf` section and,
/// when the joint was fitted, the joint section (`section` with the
/// estimates; gear_ratio 1 unless given).
ParameterFile FrfParameterFile(const ParameterFile& start, const JointSection& section, const FrfResult& result);

/// The analysis a command's choices ask for (`frf`'s flags).
struct FrfRequest {
  double resolution = 0.0, period = 0.0;  ///< [Hz], [s]; 0: chosen from the data
  std::string method = "auto";            ///< welch, periodic or auto
  bool fit = false;                       ///< fit the two-mass joint
  bool zero_order_hold = true;            ///< the drive holds its torque between samples
  std::vector<std::string> free;          ///< the two-mass fit's free set
  std::string link_is = "position";       ///< what the link signal is
  std::vector<double> band;               ///< {LO, HI} [Hz] of the fit, or empty
  /// A known method, a band of two frequencies with LO < HI.
  bool IsValid(std::string* error) const;
};

/// The analysis options of `request` (method, fit, hold, free set, link
/// quantity, band); OptionError naming the field that is wrong.
FrfOptions MakeFrfOptions(const FrfRequest& request);

/// What `frf` writes and prints: the parameter file (with the fit section
/// when the joint was fitted), the trace CSV and the Bode panels when asked
/// for, and the summary — the response's and the fit table, or one JSON
/// document. Without a fit, the response's warnings are the fit's.
struct FrfOutputs {
  std::string parameter_file, trace_csv, summary;
  std::vector<PlotPanel> panels;
  FitResult fit;
};
FrfOutputs AssembleFrfOutputs(const ParameterFile& start, const JointSection& section, const FrfResult& result,
                              const FitProvenance& provenance, bool trace, bool plot, bool json);

}  // namespace driveid
