// The subcommands of the tools register themselves, one line in each
// command's file, and main() builds the command tree from the registry:
//   const bool kRegistered = RegisterCommand(Command<AxisOptions>("drivetrain-fit", "", 10, Setup, Run));
// A new model's subcommand is its own file plus that line (and its CMake entry).
// Each declaration has options of its own, so that commands run in-process
// (the Python module, apps/common/in_process.h) may run on several threads.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

namespace driveid::cli {

struct CommandRegistration {
  std::string tool;   ///< "drivetrain-fit" or "cdrive-fit"
  std::string group;  ///< "" or the group it belongs to ("simulate")
  int order = 0;      ///< position in --help among its siblings
  /// Declares the subcommand (and options of its own) on its parent; returns
  /// it and the function that runs it with the exact command line (for provenance).
  std::function<std::pair<CLI::App*, std::function<void(const std::string& command_line)>>(CLI::App& parent)> declare;
};

/// A registration whose options are an `Options` made for each declaration:
/// `setup(parent, options)` declares it, `run(options, command_line)` runs it.
template <class Options, class Setup, class Run>
CommandRegistration Command(std::string tool, std::string group, int order, Setup setup, Run run) {
  return {std::move(tool), std::move(group), order, [setup, run](CLI::App& parent) {
            auto options = std::make_shared<Options>();
            CLI::App* command = setup(parent, *options);
            return std::make_pair(command, std::function<void(const std::string&)>(
                                               [options, run](const std::string& line) { run(*options, line); }));
          }};
}

/// Adds a subcommand; call from a namespace-scope initialiser.
bool RegisterCommand(CommandRegistration registration);

/// Declares a group of subcommands (e.g. `simulate`) with its description.
bool RegisterGroup(const std::string& tool, const std::string& group, int order, const std::string& description);

/// Declares every registered subcommand of `tool` on `app`; the returned
/// function runs the one that was given on the command line.
std::function<void(const std::string& command_line)> SetupCommands(CLI::App& app, const std::string& tool);

/// Declares only the subcommand of `tool` that `words` (the arguments) name
/// first — a command, or a group and one of its members — or every one when
/// they name none; the returned function runs it. For a run in-process,
/// which would otherwise declare the whole tree each time.
std::function<void(const std::string& command_line)> SetupCommand(CLI::App& app, const std::string& tool,
                                                                   const std::vector<std::string>& words);

}  // namespace driveid::cli
