#include "workflow/validation_run.h"

#include <fmt/format.h>

#include "core/errors.h"
#include "params/serial_robot_section.h"
#include "core/option_check.h"
#include "export/export_target.h"
#include "models/missing_values.h"
#include "sim/mujoco_axis_simulator.h"

namespace driveid {

bool AxisValidationOptions::IsValid(std::string* error) const {
  return OptionCheck(error)
      .Require(NotNegative(cutoff), "‹cutoff›", cutoff, "cutoff > 0 Hz (0: the candidate that predicts best)")
      .Require(decimation >= 0, "‹decimation›", decimation, ">= 1 (0: from the logs)")
      .Require(torque_timing != AxisTorqueTiming::kFromData,
               "‹torque_timing› auto: a validation takes the timing the fit chose (the file's, sampled, held or a "
               "delay)")
      .Require(std::abs(torque_delay) <= kMaxTorqueDelay, "‹torque_timing›", torque_delay, "a delay from -1 to 1 samples");
}

ValidationModel ChooseValidationModel(const ParameterFile* file, bool mjcf, const std::string& path,
                                      const std::string& requested) {
  if (mjcf) {
    if (!requested.empty() && requested != "axis" && requested != "joint" && requested != "robot") {
      throw OptionError(fmt::format("‹model› {}: an MJCF is validated as an axis, an elastic joint or a robot", requested));
    }
    std::string why;
    if (!MujocoAvailable(&why)) throw InputError(fmt::format("{}: {}", path, why));
    if (requested == "robot") return ValidationModel::kSerialRobot;
    return requested == "joint" ? ValidationModel::kJoint : ValidationModel::kAxis;
  }
  const bool axis = file != nullptr && file->Find<AxisSection>() != nullptr;
  const bool drivetrain = file != nullptr && file->Find<DriveTrainSection>() != nullptr;
  const bool serial = file != nullptr && file->Find<SerialRobotSection>() != nullptr;
  std::string model = requested;
  if (model.empty() && serial && !axis && !drivetrain) model = "robot";
  if (model == "robot") {
    if (!serial) throw InputError(fmt::format("{}: no 'serial_robot' section (written by drivetrain-fit robot ‹urdf›)", path));
    return ValidationModel::kSerialRobot;
  }
  if (model.empty()) {
    if (axis && drivetrain) {
      throw OptionError(
          fmt::format("{} has an axis and a drivetrain section: give ‹model› axis or ‹model› step", path));
    }
    model = axis ? "axis" : "step";
  }
  if (model == "joint") {
    throw OptionError(fmt::format("‹model› joint: an elastic joint is validated from its MJCF in MuJoCo "
                                  "(drivetrain-fit export P.yaml ‹to› {}), not from a parameter file",
                                  ExportTargetName(ExportTarget::kMjcf)));
  }
  if (model == "axis" && !axis) throw InputError(fmt::format("{}: no 'axis' section", path));
  if (model == "step" && !drivetrain) throw InputError(fmt::format("{}: no 'drivetrain' section", path));
  return model == "axis" ? ValidationModel::kAxis : ValidationModel::kStep;
}

ValidationRun RunAxisValidation(const std::vector<AxisLog>& logs, const AxisSection& axis, const std::string& path,
                                const AxisValidationOptions& options) {
  RequireValid(options);
  RequireModelValues(AxisParameterTable(), axis, path, "axis", "the prediction", AxisTermsZeroUnlessGiven(axis));
  const AxisParameters params = MakeModelParameters(AxisParameterTable(), axis, AxisParameters{}, "axis");
  if (options.simulate) {
    return {ValidateAxisBySimulation(logs, params),
            "axis simulation from the logged torque (held per sample, Coulomb friction that sticks)",
            "axis validation: position simulated from the logged torque",
            axis.linear ? "position [m]" : "position [rad]"};
  }
  AxisTorqueTiming timing = options.torque_timing;
  double delay = options.torque_delay;
  std::string source = "given";
  if (options.timing_from_file && axis.torque_delay) {
    if (!(std::abs(*axis.torque_delay) <= kMaxTorqueDelay)) {
      throw InputError(fmt::format("{}: axis.torque_delay = {}: from -1 to 1 samples", path, *axis.torque_delay));
    }
    timing = AxisTorqueTiming::kDelayed;
    delay = *axis.torque_delay;
    source = "the fit's, from the file";
  } else if (options.timing_from_file) {
    source = "the file records none";
  }
  const int decimation = AxisDecimationFor(logs, options.decimation, nullptr);
  const double cutoff = options.cutoff > 0.0 ? options.cutoff
                                             : ChooseAxisValidationCutoff(logs, params, decimation, timing, delay);
  return {ValidateAxis(logs, params, cutoff, decimation, timing, AxisReach::kAtCutoff, delay),
          fmt::format("axis inverse dynamics, position cutoff {:.4g} Hz ({}), torque {} ({})", cutoff,
                      options.cutoff > 0.0 ? "given" : "the candidate that predicts best",
                      DescribeAxisTorqueTiming(timing, delay), source),
          "axis validation: inverse dynamics (filtered, decimated)", "force or torque"};
}

ValidationRun RunStepValidation(const std::vector<StepLog>& logs, const DriveTrainSection& section,
                                DriveTrainModel model) {
  const std::string name = model == DriveTrainModel::kFull ? "full" : "reduced";
  return {ValidateSteps(logs, MakeDriveTrainParameters(section), model),
          fmt::format("drive-train simulation ({} model) from tau_motor", name),
          fmt::format("drive-train validation: simulation from the motor torque ({} model)", name),
          "link torque [N m]"};
}

ValidationRun RunMujocoValidation(const std::vector<AxisLog>& logs, const std::string& mjcf, const std::string& joint,
                                  double max_step) {
  MujocoAxisOptions mujoco;
  mujoco.joint = joint;
  mujoco.max_step = max_step;
  return {ValidateMujocoAxis(logs, mjcf, mujoco),
          fmt::format("MuJoCo simulation of joint '{}' from the logged effort (held per sample, step <= {:g} s)",
                      joint, max_step),
          "axis validation in MuJoCo: position simulated from the logged effort", "position"};
}

ValidationRun RunMujocoJointValidation(const std::vector<JointLog>& logs, const std::string& mjcf,
                                       const std::string& joint, double max_step) {
  return {ValidateMujocoJoint(logs, mjcf, joint, max_step),
          fmt::format("MuJoCo simulation of the elastic joint '{}' (motor '{}_motor') from the logged motor torque "
                      "(held per sample, step <= {:g} s)",
                      joint, joint, max_step),
          "elastic joint in MuJoCo: motor and link angles simulated from the motor torque", "angle [rad]"};
}

ValidationRun RunCDriveValidation(const std::vector<CDriveLog>& logs, const CDriveSection& section,
                                  const std::string& path, const CDriveFitOptions& prediction) {
  RequireModelValues(CDriveParameterTable(), section, path, "cdrive", "the prediction");
  const CDriveParameters params = MakeModelParameters(CDriveParameterTable(), section, CDriveParameters{}, "cdrive");
  return {ValidateCDrive(logs, params, prediction),
          fmt::format("C-drive inverse dynamics (eq. 28), differentiator half window {} s", prediction.half_window),
          "C-drive validation: motor torques by inverse dynamics", "motor torque [N m]"};
}

ValidationOutputs AssembleValidationOutputs(const std::string& program, const std::string& method,
                                            const std::vector<ValidatedLog>& logs) {
  RequireValidated(logs);
  ValidationOutputs out;
  out.trace_csv = fmt::format("# {} validate: {} (docs/models.md#validation)\nlog,t,measured,predicted,residual\n",
                              program, method);
  for (std::size_t i = 0; i < logs.size(); ++i) {
    const ValidatedLog& v = logs[i];
    out.stats.push_back(v.stats);
    out.series.push_back({v.stats.name, v.time, v.measured, v.model});
    for (std::size_t k = 0; k < v.time.size(); ++k) {
      out.trace_csv += fmt::format("{},{},{:.7g},{:.7g},{:.7g}\n", i + 1, v.time[k], v.measured[k], v.model[k],
                                   v.measured[k] - v.model[k]);
    }
  }
  return out;
}

std::vector<std::string> LogsBelowFit(const std::vector<ChannelStatistics>& stats, double threshold) {
  std::vector<std::string> below;
  for (const auto& s : stats) {
    if (!(s.fit_percent >= threshold)) below.push_back(fmt::format("{} ({:.3g} %)", s.name, s.fit_percent));
  }
  return below;
}

}  // namespace driveid
