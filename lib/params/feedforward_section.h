// The feed-forward section (models/feedforward.h; docs/formats.md): the
// gains with their std and units, written by the axis fit and `gains`,
// read back for `report` and `export`.
#pragma once

#include <string>

#include <yaml-cpp/yaml.h>

#include "models/feedforward.h"

namespace driveid {

/// Reads the section `feedforward` (InputError "file:line:column: feedforward...: what").
Feedforward ParseFeedforward(const std::string& path, const YAML::Node& node);
/// Writes it, reading back unchanged.
std::string FormatFeedforward(const Feedforward& feedforward);

}  // namespace driveid
