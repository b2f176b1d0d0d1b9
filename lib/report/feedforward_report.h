// The feed-forward section (models/feedforward.h, docs/models.md#feed-forward)
// as `report` prints it: text and JSON.
#pragma once

#include <string>

#include "models/feedforward.h"
#include "report/json.h"

namespace driveid {

/// `report` text: the law and one line per gain, value +- std and unit.
std::string FormatFeedforwardReport(const Feedforward& feedforward);
/// `report --json`: {effort_unit, position_unit, gains: {key: {value, std, unit}}}.
Json FeedforwardReportJson(const Feedforward& feedforward);

}  // namespace driveid
