// `cdrive-fit simulate` as one library call (seed 001 IV.C-F): a Table II
// motion program run in closed loop at the controller rate from a
// parameter file's cdrive and control sections; the log's text, the
// tracking errors' trace and plot panels, and the summary as text and JSON.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "params/parameter_file.h"
#include "report/json.h"
#include "report/plot.h"

namespace driveid {

struct CDriveSimulationRequest {
  std::string program;  ///< translation, rotation or helical (Table II)
  double stroke = 1.0;  ///< T [s]; one cycle is 2 T
  int cycles = 1;
  double noise = 0.0;   ///< std of the logged torques' noise [N m]
  std::uint64_t seed = 1;
  std::string law;      ///< PI, PD or PID overriding cdrive.control.law; "" keeps it
  bool trace = false;   ///< build the trace CSV (as the other runs' requests)
  bool plot = false;    ///< build the plot panels
  /// A Table II program, a known law; stroke, cycles and noise as
  /// ClosedLoopOptions::IsValid bounds them.
  bool IsValid(std::string* error) const;
};

struct CDriveSimulation {
  std::string log_text;           ///< the C-drive log (docs/formats.md#logs) with comments: command, settings, truth
  std::string trace_csv;          ///< tracking errors in u [m] and theta [rad]
  std::vector<PlotPanel> panels;  ///< the tracking errors (u in mm)
  std::string summary;            ///< one line: end-point and largest errors, switches
  Json summary_json;
};

/// Throws InputError naming `path` for a missing or incomplete cdrive
/// section, OptionError (via ClosedLoopOptions::IsValid) for the settings.
CDriveSimulation SimulateCDrive(const ParameterFile& file, const std::string& path,
                                const CDriveSimulationRequest& request, const std::string& command_line);

}  // namespace driveid
