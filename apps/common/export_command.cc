// drivetrain-fit export: a fitted axis' (or elastic joint's) parameter file
// written for MuJoCo, URDF, WPILib (Java, C++), firmware (C header) or as
// JSON; cdrive-fit export: the C-drive's compensation law (31) as a C header
// or JSON (docs/export.md).
// Parse, call the library, write: the formats live in export/parameter_export.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/cli_support.h"
#include "common/command_registry.h"
#include "core/option_check.h"
#include "export/parameter_export.h"
#include "system/atomic_file.h"
#include "params/parameter_file.h"
#include "params/serial_robot_section.h"

namespace driveid::cli {
namespace {

struct ExportCommandOptions {
  std::string params;
  std::string target;
  std::string joint = "axis";
  std::string output;
  std::string urdf;
};


CLI::App* SetupExportCommand(CLI::App& parent, ExportCommandOptions& options) {
  CLI::App* command = parent.add_subcommand(
      "export", "Write a fitted axis' parameters for MuJoCo (MJCF), URDF, WPILib Java or C++, a C header or JSON, an "
                "elastic joint's for MJCF, URDF or a C header, or a serial robot's for URDF or MJCF, with std and provenance in comments; what a target "
                "cannot hold is said in the file (docs/export.md)");
  command->add_option("params", options.params,
                      "parameter file with an axis and a feedforward section (drivetrain-fit axis -o), a joint "
                      "section (drivetrain-fit joint -o) or a serial_robot section (drivetrain-fit robot --urdf -o)")
      ->required();
  command->add_option("--to", options.target, ListExportTargets())->required()->check(CLI::IsMember(ExportTargetNames()));
  command->add_option("--joint", options.joint,
                      "joint name in MJCF/URDF, class prefix in Java, namespace prefix in C++, macro prefix in C (letters, digits, _)")
      ->capture_default_str();
  command->add_option("--urdf", options.urdf,
                      "serial robot: the URDF it was fitted on (default: the one its serial_robot section names; its "
                      "SHA-256 must match)");
  command->add_option("-o,--output", options.output, "file to write (default: stdout); written atomically");
  command->footer("Example:\n  drivetrain-fit axis data/axis_steps.csv -o axis.yaml\n"
                  "  drivetrain-fit export axis.yaml --to mjcf --joint shoulder -o shoulder.xml\n"
                  "  drivetrain-fit export data/joint_example_truth.yaml --to mjcf --joint elbow -o elbow.xml\n"
                  "  drivetrain-fit export arm.yaml --to urdf -o arm_identified.urdf   # a robot --urdf fit");
  return command;
}

CLI::App* SetupCDriveExportCommand(CLI::App& parent, ExportCommandOptions& options) {
  options.joint = "cdrive";
  CLI::App* command = parent.add_subcommand(
      "export", "Write a fitted C-drive's compensation law (31) as a C header or JSON, with std and provenance "
                "(docs/export.md#c-drive); MJCF, URDF and WPILib have no form for it");
  command->add_option("params", options.params, "parameter file with a cdrive feedforward section (cdrive-fit friction -o)")
      ->required();
  const std::vector<ExportTarget> cdrive_targets{ExportTarget::kCHeader, ExportTarget::kJson};
  command->add_option("--to", options.target, ListExportTargets(cdrive_targets))
      ->required()
      ->check(CLI::IsMember(ExportTargetNames(cdrive_targets)));
  command->add_option("--joint", options.joint, "macro prefix in C, name in JSON (letters, digits, _)")
      ->capture_default_str();
  command->add_option("-o,--output", options.output, "file to write (default: stdout); written atomically");
  command->footer("Example:\n  cdrive-fit friction data/cdrive_slow_*.csv --params data/cdrive_start.yaml -o friction.yaml\n"
                  "  cdrive-fit export friction.yaml --to c-header -o cdrive_compensation.h");
  return command;
}

void RunExportCommand(const ExportCommandOptions& options, const std::string& command_line) {
  ExportOptions export_opts;
  export_opts.joint = options.joint;
  export_opts.source = options.params;
  export_opts.command = command_line;
  export_opts.urdf = options.urdf;
  RequireValid(export_opts);
  CheckDistinctFiles({options.params, options.urdf}, {{"-o", options.output}});
  const ParameterFile file = ReadParameterFile(options.params);
  if (const SerialRobotSection* robot = file.Find<SerialRobotSection>(); robot != nullptr && options.urdf.empty()) {
    CheckDistinctFiles({robot->urdf}, {{"-o", options.output}});
  }
  const std::string text = ExportParameters(file, ParseExportTarget(options.target), export_opts);
  if (options.output.empty()) WriteStdout(text);
  else WriteFileAtomically(options.output, ShowFlags(text));
}

const bool kDrivetrain = RegisterCommand(Command<ExportCommandOptions>(
    "drivetrain-fit", "", 55, [](CLI::App& parent, ExportCommandOptions& o) { return SetupExportCommand(parent, o); },
    [](const ExportCommandOptions& o, const std::string& line) { RunExportCommand(o, line); }));
const bool kCDrive = RegisterCommand(Command<ExportCommandOptions>(
    "cdrive-fit", "", 55, [](CLI::App& parent, ExportCommandOptions& o) { return SetupCDriveExportCommand(parent, o); },
    [](const ExportCommandOptions& o, const std::string& line) { RunExportCommand(o, line); }));

}  // namespace
}  // namespace driveid::cli
