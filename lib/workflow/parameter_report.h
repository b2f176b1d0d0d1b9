// `drivetrain-fit report` as one library call: a parameter file's derived
// quantities, one block per section it holds (the robot at a pose, the
// drive train beside a fitted file, the feed-forward, joint, frf and
// feedback sections), and a fitted file's estimates compared with the
// file's; as text and as one JSON document with a member per section.
// Documented in docs/formats.md#parameter-files.
#pragma once

#include <optional>
#include <string>

#include "params/parameter_file.h"
#include "models/planar_robot.h"
#include "report/json.h"

namespace driveid {

struct ParameterReportRequest {
  std::string path;                  ///< the file's, for messages and the drive train's column
  const ParameterFile* fitted = nullptr;
  std::string fitted_path;
  std::optional<Vector2> pose;       ///< robot: centre joint [m]; default the workspace centre
  std::optional<Vector2> velocity;   ///< robot: centre joint velocity [m/s]; default 0
  /// A fitted file comes with its path; a pose and velocity are finite.
  bool IsValid(std::string* error) const;
};

struct ParameterReport {
  std::string text;            ///< without `json`
  Json json = Json::object();  ///< with `json`
};

/// The text, or with `json` the JSON document. InputError naming the file
/// when it has none of the sections, or when a fitted file lacks what it is
/// read for; OptionError naming ‹pose› for a pose outside the workspace.
ParameterReport ReportParameterFile(const ParameterFile& file, const ParameterReportRequest& request, bool json);

}  // namespace driveid
