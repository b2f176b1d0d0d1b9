// Step logs (docs/formats.md): t, tau_motor, tau_link; optional q_motor (motor
// encoder) and q_link (gear output angle), which separate k_Tl and k_Tg.
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

namespace driveid {

struct CsvLog;

/// Fewest samples the step fit accepts in a log.
inline constexpr std::size_t kMinStepLogSamples = 3;

/// A logged step response (docs/formats.md#logs, step log).
struct StepLog {
  std::string path;
  std::vector<double> time;          ///< t [s], strictly increasing
  std::vector<double> motor_torque;  ///< tau_motor [N m], held between samples
  std::vector<double> link_torque;   ///< tau_link [N m], strain gauge
  std::vector<double> motor_angle;   ///< q_motor [rad], motor encoder = n_g phi (optional: empty)
  std::vector<double> link_angle;    ///< q_link [rad], gear output (link root) angle = Delta (optional)
};

/// The logical columns of the log (an entry "a|b": a, or else b).
const std::vector<std::string>& StepLogColumns();

/// The log from columns read by ReadLogs (logs/log_input.h) with StepLogColumns().
/// Throws InputError.
StepLog MakeStepLog(CsvLog csv);

/// Parses a step log already read into memory; `column_map` from --col.
/// Throws InputError.
StepLog ParseStepLog(const std::string& path, const std::string& text,
                     const std::map<std::string, std::string>& column_map = {});

/// Formats a step log as CSV with '#' comment lines first.
std::string FormatStepLog(const StepLog& log, const std::vector<std::string>& comments);

}  // namespace driveid
