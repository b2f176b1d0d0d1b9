// Axis logs (docs/formats.md): t, q and tau, or i with k_t; optional qd and
// tau_known (a known torque, subtracted).
#pragma once

#include <array>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace driveid {

struct CsvLog;

/// Fewest samples the axis fit accepts in a log: a SysIdRoutine's dynamic
/// test of 7 V on an arm or elevator lasts 0.3-0.5 s, 15-25 samples at 50
/// Hz, and is what determines Ka; 10 leave the differentiator (central
/// differences, one sample lost at each end) 8 rates and the rows' reach.
inline constexpr std::size_t kMinAxisLogSamples = 10;

struct AxisLog {
  std::string path;
  std::vector<double> time;      ///< [s]
  std::vector<double> position;  ///< q [rad or m]
  std::vector<double> force;     ///< tau [N m or N] (from i x k_t if given as current) minus tau_known if logged
  std::vector<double> rate;      ///< qd [rad/s or m/s], a measured rate (empty: q is differentiated)
  /// Rows where q and qd were measured (empty: every row). Rows in between
  /// carry the effort only (e.g. a logger's rows between a device's status
  /// frames, signal/held_samples.h); output error compares the measured rows.
  std::vector<char> measured{};
  /// The logged rate's first value when the rate channel was left out (a
  /// rate held between status frames), for where a simulation starts; NaN:
  /// none (the start rate then comes from `rate` or the position).
  double start_rate = std::numeric_limits<double>::quiet_NaN();
};

/// The logical columns of the log (an entry "a|b": a, or else b).
const std::vector<std::string>& AxisLogColumns();

/// The log from columns read by ReadLogs (logs/log_input.h) with AxisLogColumns().
/// Throws InputError.
AxisLog MakeAxisLog(CsvLog csv, double torque_constant);

/// Parses an axis log: t, q and tau, or i with `torque_constant`. Throws InputError.
AxisLog ParseAxisLog(const std::string& path, const std::string& text,
                     const std::map<std::string, std::string>& column_map, double torque_constant);

/// Formats an axis log as CSV with '#' comment lines first.
std::string FormatAxisLog(const AxisLog& log, const std::vector<std::string>& comments);

}  // namespace driveid
