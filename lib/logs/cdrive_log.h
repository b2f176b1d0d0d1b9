// C-drive logs (docs/formats.md): t, psi_L, psi_R, tau_L, tau_R (or i_L, i_R with k_t).
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

namespace driveid {

struct CsvLog;

/// A C-drive log (docs/formats.md#logs): motor angles and torques (or currents x k_t).
/// Fewest samples the C-drive fits accept in a log.
inline constexpr std::size_t kMinCDriveLogSamples = 5;

struct CDriveLog {
  std::string path;
  std::vector<double> time;         ///< [s]
  std::vector<double> angle_left;   ///< psi_L [rad]
  std::vector<double> angle_right;  ///< psi_R [rad]
  std::vector<double> torque_left;  ///< tau_L [N m]
  std::vector<double> torque_right; ///< tau_R [N m]
};

/// The logical columns of the log (an entry "a|b": a, or else b).
const std::vector<std::string>& CDriveLogColumns();

/// The log from columns read by ReadLogs (logs/log_input.h) with CDriveLogColumns().
/// Throws InputError.
CDriveLog MakeCDriveLog(CsvLog csv, double torque_constant);

/// Parses a C-drive log; columns t, psi_L, psi_R and tau_L, tau_R or i_L,
/// i_R (then `torque_constant` k_t [N m/A] must be given). Throws InputError.
CDriveLog ParseCDriveLog(const std::string& path, const std::string& text,
                         const std::map<std::string, std::string>& column_map, double torque_constant);

/// Formats a C-drive log as CSV with '#' comment lines first.
std::string FormatCDriveLog(const CDriveLog& log, const std::vector<std::string>& comments);

}  // namespace driveid
