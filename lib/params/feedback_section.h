// The `feedback` section of a parameter file (models/feedback.h,
// docs/formats.md#feedback): read strictly (unknown keys, non-numbers and
// hostile unit names refused by file:line:column) and written so that it
// reads back unchanged.
#pragma once

#include <string>

#include <yaml-cpp/yaml.h>

#include "models/feedback.h"

namespace driveid {

FeedbackController ParseFeedbackSection(const std::string& path, const YAML::Node& node);
/// OutputError (nothing written) for an unknown loop, key or a unit that is no unit name.
std::string FormatFeedbackSection(const FeedbackController& feedback);

}  // namespace driveid
