// An axis' feed-forward section (models/feedforward.h) as WPILib's
// feed-forward classes take it (docs/export.md): SimpleMotorFeedforward(kS,
// kV, kA), ArmFeedforward(kS, kG, kV, kA) when gravity was fitted on a
// rotary axis, ElevatorFeedforward(kS, kG, kV, kA) for a linear axis with a
// constant force (the offset); per direction where friction was fitted so.
//   Java: plain doubles in the log's units, a class with factory methods;
//   C++:  the units library's types in the log's units (the position unit
//         mapped to units::radians, turns, degrees, meters, feet, inches),
//         so WPILib's own types convert where its class fixes the unit
//         (ArmFeedforward: radians, ElevatorFeedforward: meters); volts only.
#pragma once

#include <string>
#include <vector>

#include "export/export_target.h"
#include "export/export_text.h"
#include "params/parameter_file.h"

namespace driveid {

struct WpilibAxis {
  const Feedforward& feedforward;
  bool linear = false;
  /// What WPILib's classes cannot hold of the fitted terms, one note each
  /// (models/axis_term.h ExportNote).
  std::vector<std::string> term_notes;
  const FeedbackController* feedback = nullptr;  ///< gains' section, if any: PIDController constants
};

std::string ExportWpilibJava(const WpilibAxis& axis, const ExportOptions& options);

/// Throws InputError when the effort is not in volts or the position unit
/// has no units-library type.
std::string ExportWpilibCpp(const WpilibAxis& axis, const ExportOptions& options);

}  // namespace driveid
