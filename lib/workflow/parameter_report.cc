#include "workflow/parameter_report.h"

#include <cmath>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"
#include "report/drivetrain_report.h"
#include "report/feedback_report.h"
#include "report/feedforward_report.h"
#include "report/joint_report.h"
#include "report/parameter_comparison.h"
#include "workflow/drift_comparison.h"
#include "report/planar_robot_report.h"

namespace driveid {

namespace {

void AddRobot(const ParameterFile& file, const ParameterReportRequest& r, bool json, ParameterReport& out) {
  const PlanarRobotParameters robot = MakePlanarRobotParameters(*file.Find<PlanarRobotSection>());
  const double a = robot.base_distance;
  const Vector2 pose = r.pose.value_or(Vector2{0.5 * a, a / (2.0 * std::sqrt(3.0))});
  const Vector2 velocity = r.velocity.value_or(Vector2{0.0, 0.0});
  try {
    const PlanarRobotReport report = CalcPlanarRobotReport(robot, pose, velocity, r.path);
    if (json) out.json["planar_robot"] = PlanarRobotReportJson(report);
    else out.text += FormatPlanarRobotReport(report);
  } catch (const std::domain_error& e) {
    throw OptionError(fmt::format("‹pose›: {}", e.what()));
  }
}

void AddDriveTrain(const ParameterFile& file, const ParameterReportRequest& r, bool json, ParameterReport& out) {
  if (r.fitted && !r.fitted->Find<DriveTrainSection>()) {
    throw InputError(fmt::format("{}: no 'drivetrain' section", r.fitted_path));
  }
  const DriveTrainParameters params = MakeDriveTrainParameters(*file.Find<DriveTrainSection>());
  std::optional<DriveTrainParameters> fitted_values;
  if (r.fitted) fitted_values = MakeDriveTrainParameters(*r.fitted->Find<DriveTrainSection>());
  const DriveTrainReport report =
      CalcDriveTrainReport(params, r.path, fitted_values ? &*fitted_values : nullptr, r.fitted_path);
  if (json) out.json["drivetrain"] = DriveTrainReportJson(report);
  else out.text += FormatDriveTrainReport(report);
}

// A fitted file beside a section other than the drive train: the two fits'
// estimates compared (docs/guide.md#fleets-and-drift), or a refusal.
void AddComparison(const ParameterFile& file, const ParameterReportRequest& r, bool json, ParameterReport& out) {
  const std::string& without = file.fit_estimates.empty() ? r.path : r.fitted_path;
  if (file.fit_estimates.empty() || r.fitted->fit_estimates.empty()) {
    throw InputError(fmt::format("‹fitted›: {} has no fit.estimates: beside a 'drivetrain' section ‹fitted› shows "
                                 "the fitted values in a column; for the other sections both files must be fits "
                                 "(drivetrain-fit compare)",
                                 without));
  }
  const FileComparison comparison = CompareEstimates(r.fitted_path, file.fit_estimates, r.fitted->fit_estimates, {});
  if (json) out.json["fitted"] = ComparisonsJson(r.path, {comparison}, {});
  else out.text += FormatComparisons(r.path, {comparison}, {});
}

}  // namespace

bool ParameterReportRequest::IsValid(std::string* error) const {
  const auto finite = [](const std::optional<Vector2>& v) { return !v || (Finite(v->x()) && Finite(v->y())); };
  return OptionCheck(error)
      .Require(fitted == nullptr || !fitted_path.empty(), "a fitted file needs its path")
      .Require(finite(pose), "‹pose›: not finite")
      .Require(finite(velocity), "‹velocity›: not finite");
}

ParameterReport ReportParameterFile(const ParameterFile& file, const ParameterReportRequest& r, bool json) {
  RequireValid(r);
  if (!file.Find<DriveTrainSection>() && !file.Find<PlanarRobotSection>() && file.feedforward.gains.empty() &&
      file.feedback.empty() && !file.Find<JointSection>() && !file.Find<FrequencyResponseSection>()) {
    throw InputError(fmt::format("{}: no 'drivetrain', 'planar_robot', 'feedforward', 'feedback', 'joint' or 'frf' "
                                 "section (an axis fit writes the feed-forward section, gains the feedback section)",
                                 r.path));
  }
  // Text: one block per section. JSON: one document with a member per section.
  ParameterReport out;
  if (file.Find<PlanarRobotSection>()) AddRobot(file, r, json, out);
  if (file.Find<DriveTrainSection>()) AddDriveTrain(file, r, json, out);
  if (!file.feedforward.gains.empty()) {
    if (json) out.json["feedforward"] = FeedforwardReportJson(file.feedforward);
    else out.text += FormatFeedforwardReport(file.feedforward);
  }
  if (file.Find<JointSection>() || file.Find<FrequencyResponseSection>()) {
    if (json) out.json.update(JointReportJson(file));
    else out.text += FormatJointReport(file);
  }
  if (!file.feedback.empty()) {
    if (json) out.json["feedback"] = FeedbackReportJson(file.feedback);
    else out.text += FormatFeedbackReport(file.feedback);
  }
  if (r.fitted && !file.Find<DriveTrainSection>()) AddComparison(file, r, json, out);
  return out;
}

}  // namespace driveid
