#include "drivetrain_fit/report_command.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <fmt/format.h>

#include "common/cli_support.h"
#include "common/command_registry.h"
#include "core/errors.h"
#include "io/parameter_file.h"
#include "workflow/axis_feedforward.h"
#include "report/drivetrain_report.h"
#include "workflow/feedback_design.h"
#include "report/parameter_comparison.h"
#include "report/joint_report.h"
#include "report/planar_robot_report.h"

namespace driveid::cli {

CLI::App* SetupReportCommand(CLI::App& app, ReportOptions& options) {
  CLI::App* command = app.add_subcommand(
      "report", "Transfer function (eq. 16), omega_n, zeta, gain; the paper's eq. (17) beside the recomputed values; "
      "a fitted axis' feed-forward gains (docs/models.md#feed-forward)");
  command->add_option("params", options.params, "parameter file")->required();
  command->add_option("--fitted", options.fitted,
                      "a fitted parameter file: beside a drivetrain section its values in a further column, "
                      "else its fit.estimates compared with the file's (both must be fits)");
  command->add_option("--pose", options.pose, "robot: centre joint x,y [m] (default: the workspace centre)")
      ->delimiter(',')
      ->expected(2);
  command->add_option("--velocity", options.velocity, "robot: centre joint velocity vx,vy [m/s] for C (default 0)")
      ->delimiter(',')
      ->expected(2);
  command->add_flag("--json", options.json, "print one JSON object instead of the text");
  command->footer("Example:\n  drivetrain-fit report data/paper000.yaml --fitted out/fig6_fit.yaml");
  return command;
}

void RunReportCommand(const ReportOptions& options) {
  const ParameterFile file = ReadParameterFile(options.params);
  if (!file.Find<DriveTrainSection>() && !file.Find<PlanarRobotSection>() && file.feedforward.gains.empty() &&
      file.feedback.empty() && !file.Find<JointSection>() && !file.Find<FrequencyResponseSection>()) {
    throw InputError(fmt::format("{}: no 'drivetrain', 'planar_robot', 'feedforward', 'feedback', 'joint' or 'frf' "
                                 "section (an axis fit writes the feed-forward section, gains the feedback section)",
                                 options.params));
  }
  // Text: one block per section. JSON: one document with a member per section.
  std::string text;
  Json json = Json::object();
  if (file.Find<PlanarRobotSection>()) {
    const PlanarRobotParameters robot = MakePlanarRobotParameters(*file.Find<PlanarRobotSection>());
    const double a = robot.base_distance;
    const Vector2 pose = options.pose.size() == 2 ? Vector2{options.pose[0], options.pose[1]}
                                                   : Vector2{0.5 * a, a / (2.0 * std::sqrt(3.0))};
    const Vector2 velocity = options.velocity.size() == 2 ? Vector2{options.velocity[0], options.velocity[1]}
                                                           : Vector2{0.0, 0.0};
    try {
      const PlanarRobotReport report = CalcPlanarRobotReport(robot, pose, velocity, options.params);
      if (options.json) json["planar_robot"] = PlanarRobotReportJson(report);
      else text += FormatPlanarRobotReport(report);
    } catch (const std::domain_error& e) {
      throw OptionError(fmt::format("--pose: {}", e.what()));
    }
  }
  if (file.Find<DriveTrainSection>()) {
    ParameterFile fitted;
    if (!options.fitted.empty()) {
      fitted = ReadParameterFile(options.fitted);
      if (!fitted.Find<DriveTrainSection>()) throw InputError(fmt::format("{}: no 'drivetrain' section", options.fitted));
    }
    const DriveTrainParameters params = MakeDriveTrainParameters(*file.Find<DriveTrainSection>());
    std::optional<DriveTrainParameters> fitted_values;
    if (fitted.Find<DriveTrainSection>()) fitted_values = MakeDriveTrainParameters(*fitted.Find<DriveTrainSection>());
    const DriveTrainParameters* fitted_params = fitted_values ? &*fitted_values : nullptr;
    const DriveTrainReport report = CalcDriveTrainReport(params, options.params, fitted_params, options.fitted);
    if (options.json) json["drivetrain"] = DriveTrainReportJson(report);
    else text += FormatDriveTrainReport(report);
  }
  if (!file.feedforward.gains.empty()) {
    if (options.json) json["feedforward"] = FeedforwardReportJson(file.feedforward);
    else text += FormatFeedforwardReport(file.feedforward);
  }
  if (file.Find<JointSection>() || file.Find<FrequencyResponseSection>()) {
    if (options.json) json.update(JointReportJson(file));
    else text += FormatJointReport(file);
  }
  if (!file.feedback.empty()) {
    if (options.json) json["feedback"] = FeedbackReportJson(file.feedback);
    else text += FormatFeedbackReport(file.feedback);
  }
  // --fitted beside a section other than the drive train: the two fits'
  // estimates compared (docs/guide.md#fleets-and-drift), or a refusal.
  if (!options.fitted.empty() && !file.Find<DriveTrainSection>()) {
    const ParameterFile fitted = ReadParameterFile(options.fitted);
    const std::string& without = file.fit_estimates.empty() ? options.params : options.fitted;
    if (file.fit_estimates.empty() || fitted.fit_estimates.empty()) {
      throw InputError(fmt::format("--fitted: {} has no fit.estimates: beside a 'drivetrain' section --fitted shows "
                                   "the fitted values in a column; for the other sections both files must be fits "
                                   "(drivetrain-fit compare)",
                                   without));
    }
    const FileComparison comparison = CompareEstimates(options.fitted, file.fit_estimates, fitted.fit_estimates, {});
    if (options.json) json["fitted"] = ComparisonsJson(options.params, {comparison}, {});
    else text += FormatComparisons(options.params, {comparison}, {});
  }
  WriteStdout(options.json ? DumpJson(json) : text);
}

namespace {
ReportOptions report_options;
const bool kRegistered = RegisterCommand({"drivetrain-fit", "", 50,
                                          [](CLI::App& parent) { return SetupReportCommand(parent, report_options); },
                                          [](const std::string&) { RunReportCommand(report_options); }});
}  // namespace

}  // namespace driveid::cli
