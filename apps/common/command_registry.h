// The subcommands of the tools register themselves, one line in each
// command's file, and main() builds the command tree from the registry:
//   const bool kRegistered = RegisterCommand({"drivetrain-fit", "", 10, Setup, Run});
// A new model's subcommand is its own file plus that line (and its CMake entry).
#pragma once

#include <functional>
#include <string>

#include <CLI/CLI.hpp>

namespace driveid::cli {

struct CommandRegistration {
  std::string tool;   ///< "drivetrain-fit" or "cdrive-fit"
  std::string group;  ///< "" or the group it belongs to ("simulate")
  int order = 0;      ///< position in --help among its siblings
  /// Declares the subcommand (and its options) on its parent; returns it.
  std::function<CLI::App*(CLI::App& parent)> setup;
  /// Runs it with the exact command line (for provenance).
  std::function<void(const std::string& command_line)> run;
};

/// Adds a subcommand; call from a namespace-scope initialiser.
bool RegisterCommand(CommandRegistration registration);

/// Declares a group of subcommands (e.g. `simulate`) with its description.
bool RegisterGroup(const std::string& tool, const std::string& group, int order, const std::string& description);

/// Declares every registered subcommand of `tool` on `app`; the returned
/// function runs the one that was given on the command line.
std::function<void(const std::string& command_line)> SetupCommands(CLI::App& app, const std::string& tool);

}  // namespace driveid::cli
