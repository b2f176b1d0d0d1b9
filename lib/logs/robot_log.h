// Planar robot logs (docs/formats.md): t, theta1..3, i1..3.
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

namespace driveid {

struct CsvLog;

/// Fewest samples the robot fit accepts in a log.
inline constexpr std::size_t kMinRobotLogSamples = 10;

/// A robot log (docs/formats.md#logs): joint angles at the gear output and motor currents.
struct RobotLog {
  std::string path;
  std::vector<double> time;
  std::array<std::vector<double>, 3> angle;    ///< theta_i [rad]
  std::array<std::vector<double>, 3> current;  ///< i_i [A]
  std::vector<int> line_numbers;               ///< file line of each sample (empty: not read from a file)
};

/// The logical columns of the log (an entry "a|b": a, or else b).
const std::vector<std::string>& RobotLogColumns();

/// The log from columns read by ReadLogs (logs/log_input.h) with RobotLogColumns().
/// Throws InputError.
RobotLog MakeRobotLog(CsvLog csv);

/// Parses t, theta1..3, i1..3. Throws InputError.
RobotLog ParseRobotLog(const std::string& path, const std::string& text,
                       const std::map<std::string, std::string>& column_map);

/// Formats a robot log as CSV with '#' comment lines first.
std::string FormatRobotLog(const RobotLog& log, const std::vector<std::string>& comments);

}  // namespace driveid
