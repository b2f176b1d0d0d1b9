// `drivetrain-fit frf` around its one library call (fit/frf_analysis.h):
// the names of the response's quantities, a measured response brought to
// Hz, linear magnitude and radians, a log's columns made the analysis'
// signals, and the parameter file the run writes
// (docs/models.md#frequency-response).
#pragma once

#include <string>
#include <vector>

#include "fit/frf_analysis.h"
#include "io/csv_log.h"
#include "io/parameter_file.h"

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

}  // namespace driveid
