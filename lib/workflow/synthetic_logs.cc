#include "workflow/synthetic_logs.h"

#include <stdexcept>

#include <fmt/format.h>

#include "core/errors.h"
#include "logs/axis_log.h"
#include "logs/axis_reference.h"
#include "logs/joint_log.h"
#include "logs/robot_log.h"
#include "logs/step_log.h"
#include "logs/torque_reference.h"
#include "models/missing_values.h"

namespace driveid {

std::string SyntheticStepLog(const ParameterFile& file, const std::string& path, const std::string& model,
                             StepExperiment experiment, const std::string& command_line) {
  if (!file.Find<DriveTrainSection>()) throw InputError(fmt::format("{}: no 'drivetrain' section", path));
  experiment.model = model == "full" ? DriveTrainModel::kFull : DriveTrainModel::kReduced;
  const DriveTrainParameters p = MakeDriveTrainParameters(*file.Find<DriveTrainSection>());
  if (experiment.model == DriveTrainModel::kFull && !(p.gearbox_inertia > 0.0)) {
    throw InputError(fmt::format("{}: the full model needs drivetrain.Theta_g > 0", path));
  }
  const StepLog log = SimulateStepExperiment(p, experiment);
  return FormatStepLog(
      log, {"synthetic step log (docs/formats.md#logs) made by: " + command_line,
            fmt::format("model {}, rate {} Hz, step {} N m at {} s, noise {} N m (seed {}), offset {} N m", model,
                        experiment.rate, experiment.step_torque, experiment.step_time, experiment.noise,
                        experiment.seed, experiment.offset),
            fmt::format("truth: n_g {}, k_Tl {}, k_Tg {}, Theta_motor {}, Theta_g {}, d_g {}, tau_c {}", p.gear_ratio,
                        p.link_stiffness, p.gearbox_stiffness, p.motor_inertia, p.gearbox_inertia,
                        p.viscous_friction, p.coulomb_friction)});
}

std::string SyntheticAxisLog(const ParameterFile& file, const std::string& path, AxisExperiment e,
                             const std::string& reference_path, const std::string& command_line) {
  if (!file.Find<AxisSection>()) throw InputError(fmt::format("{}: no 'axis' section", path));
  RequireModelValues(AxisParameterTable(), *file.Find<AxisSection>(), path, "axis", "the simulation",
                     AxisTermsZeroUnlessGiven(*file.Find<AxisSection>()));
  const AxisParameters params =
      MakeModelParameters(AxisParameterTable(), *file.Find<AxisSection>(), AxisParameters{}, "axis");
  if (!reference_path.empty()) {
    e.profile = "reference";
    e.reference = ReadAxisReference(reference_path);
  }
  const AxisLog log = SimulateAxisExperiment(params, e);
  return FormatAxisLog(
      log, {"synthetic axis log (docs/formats.md#logs) made by: " + command_line,
            fmt::format("profile {}, rate {} Hz, resolution {}, noise {} (seed {})", e.profile, e.rate, e.resolution,
                        e.noise, e.seed),
            fmt::format("truth: inertia {}, viscous {}, coulomb {}, offset {}", params.inertia, params.viscous,
                        params.coulomb, params.offset)});
}

std::string SyntheticRobotLog(const ParameterFile& file, const std::string& path, const RobotExperiment& r,
                              const std::string& command_line) {
  if (!file.Find<PlanarRobotSection>()) throw InputError(fmt::format("{}: no 'planar_robot' section", path));
  RobotLog log;
  try {
    log = SimulateRobotExperiment(MakePlanarRobotParameters(*file.Find<PlanarRobotSection>()), r);
  } catch (const std::domain_error& e) {
    throw InputError(fmt::format("{}: the triangle leaves the workspace: {}", path, e.what()));
  }
  const PlanarRobotParameters p = MakePlanarRobotParameters(*file.Find<PlanarRobotSection>());
  return FormatRobotLog(
      log, {"synthetic robot log (docs/formats.md#logs) made by: " + command_line,
            fmt::format("triangle side {} m, {} m/s^2, {} m/s, dwell {} s, {} loops, {} Hz, 13-bit encoders behind the "
                        "gears, prestress {} N m, current noise {} A (seed {})",
                        r.side, r.acceleration, r.speed, r.dwell, r.loops, r.rate, r.prestress, r.current_noise, r.seed),
            fmt::format("truth: Theta {}, m_c {}, d_g {}, n_g {}, k_t {}", p.output_inertia, p.center_mass,
                        p.viscous_friction, p.gear_ratio, p.torque_constant)});
}

std::string SyntheticJointLog(const ParameterFile& file, const std::string& path, JointExperiment e,
                              const std::string& reference_path, bool duration_given, const std::string& command_line) {
  if (!file.Find<JointSection>()) throw InputError(fmt::format("{}: no 'joint' section", path));
  const JointSection& section = *file.Find<JointSection>();
  const JointParameters p = ModelValuesOr(JointParameterTable(), section, 0.0);
  if (!reference_path.empty()) {
    const TorqueReference reference = ReadTorqueReference(reference_path);
    e.excitation = "reference";
    e.reference = reference.torque;
    e.rate = TorqueReferenceRate(reference);
    if (!duration_given) e.duration = static_cast<double>(reference.torque.size()) / e.rate;
  }
  const double n = section.gear_ratio.value_or(1.0);
  const JointExperimentLog log = SimulateJointExperiment(p, n, e);
  return FormatJointExperimentLog(
      log, {"synthetic joint log (docs/formats.md#logs) made by: " + command_line,
            fmt::format("{} {} .. {} Hz, period {} s, rms {} N m; PI speed loop kp {} ki {}; rate {} Hz; speed noise {} "
                        "rad/s (seed {}); r is the injected excitation",
                        e.excitation, e.f_low, e.f_high, e.period, e.amplitude, e.kp, e.ki, e.rate, e.noise, e.seed),
            fmt::format("truth (link side): n {}, J_m {}, J_l {}, k {}, d {}, b_m {}, c_m {}, b_l {}, c_l {}", n,
                        p.motor_inertia, p.link_inertia, p.stiffness, p.damping, p.motor_viscous, p.motor_coulomb,
                        p.link_viscous, p.link_coulomb)});
}

}  // namespace driveid
