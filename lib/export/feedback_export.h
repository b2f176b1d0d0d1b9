// The feedback section (models/feedback.h, written by `gains`) in the export
// targets (docs/export.md#feedback): C header constants (and the speed
// loop's C(s) coefficients), WPILib Java/C++ PIDController constants with the
// vendor's slot settings as a comment. Empty strings when the file has none.
#pragma once

#include <string>

#include "models/feedback.h"
#include "report/json.h"

namespace driveid {

/// DRIVEID_CONSTANT <UPPER>_FEEDBACK_KP ... lines (kp, kd, ki, period, notch,
/// C(s) numerator/denominator coefficients NUM0.. highest power first).
std::string FeedbackCHeaderLines(const FeedbackController& feedback, const std::string& upper);

/// Java members: kP, kD, kControllerPeriodSeconds and pidController(); for
/// a speed loop kP, kI, the period, the notch and C(z) as arrays with the
/// difference equation (no PIDController holds its notch). Refuses
/// (InputError) a section without the values it writes.
std::string FeedbackJavaMembers(const FeedbackController& feedback);
/// The import the members need, or "".
std::string FeedbackJavaImport(const FeedbackController& feedback);

/// C++ (namespace scope): kP, kD, kControllerPeriod and MakePIDController();
/// a speed loop as in Java, C(z) as std::array.
std::string FeedbackCppMembers(const FeedbackController& feedback);
std::string FeedbackCppInclude(const FeedbackController& feedback);

/// The section as JSON: loop, preset, units, each value with its std and
/// unit, C(s) and C(z); null when the file has none.
Json FeedbackJson(const FeedbackController& feedback);

/// A comment on how the preset's controller takes the gains ("" for wpilib).
std::string FeedbackVendorNote(const FeedbackController& feedback, const char* comment);

}  // namespace driveid
