// The runs of `drivetrain-fit simulate`: a synthetic log of each model made
// from a parameter file's section and an experiment (sim/*_experiment.h),
// as the text of the log in its input format (docs/formats.md#logs), its
// comment lines naming the command line, the settings and the truth.
#pragma once

#include <string>

#include "params/parameter_file.h"
#include "sim/axis_experiment.h"
#include "sim/joint_experiment.h"
#include "sim/robot_experiment.h"
#include "sim/step_experiment.h"

namespace driveid {

/// A step log of the file's drivetrain section (`model`: reduced or full).
/// InputError naming `path` for a missing section or a full model without Theta_g.
std::string SyntheticStepLog(const ParameterFile& file, const std::string& path, const std::string& model,
                             StepExperiment experiment, const std::string& command_line);

/// An axis log of the file's axis section, following `reference_path`'s
/// reference (docs/formats.md#references) when it is not empty.
std::string SyntheticAxisLog(const ParameterFile& file, const std::string& path, AxisExperiment experiment,
                             const std::string& reference_path, const std::string& command_line);

/// A robot log of the file's planar_robot section along the triangle;
/// InputError when the triangle leaves the workspace.
std::string SyntheticRobotLog(const ParameterFile& file, const std::string& path, const RobotExperiment& experiment,
                              const std::string& command_line);

/// A joint log of the file's joint section: injecting `reference_path`'s
/// torque (t,tau, repeated) when it is not empty, over its own length
/// unless `duration_given`.
std::string SyntheticJointLog(const ParameterFile& file, const std::string& path, JointExperiment experiment,
                              const std::string& reference_path, bool duration_given, const std::string& command_line);

}  // namespace driveid
