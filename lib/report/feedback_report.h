// The feedback section (models/feedback.h, docs/models.md#feedback-gains) as
// `gains` and `report` print it: text and JSON.
#pragma once

#include <string>

#include "models/feedback.h"
#include "report/json.h"

namespace driveid {

/// The text `gains` prints: the gains with their std and units, the plant
/// and the settings they came from.
std::string FormatFeedbackReport(const FeedbackController& feedback);
/// {loop, preset, effort_unit, position_unit, feedback: {kp: {value, std}, ...}, settings..., controller...}.
Json FeedbackReportJson(const FeedbackController& feedback);

}  // namespace driveid
