// A command of the tools run inside this process, as its main() would run
// it from the same arguments (the Python module, docs/python.md): the same
// parsing, validation and computation, so the same numbers to the last bit,
// with standard output and the fits' outputs captured rather than printed,
// logs optionally given in memory, and the exit code and message returned
// rather than printed. Each run has options of its own
// (common/command_registry.h): runs on several threads do not meet.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "common/cli_support.h"
#include "common/log_input_options.h"

namespace driveid::cli {

struct InProcessResult {
  int code = kSuccess;                  ///< the exit code main() would return
  std::string message;                  ///< the error message (flags shown), "" on success
  std::vector<std::string> parameters;  ///< an identification refusal's parameters
  std::string out;                      ///< what went to standard output
  std::vector<FitOutputs> fits;         ///< each fit's outputs, as written
};

/// Runs `tool` (e.g. "drivetrain-fit") with `args` (the arguments after the
/// tool's name); `command_line` is recorded as the run's provenance. Logs
/// named as one of `given` are read from memory. Standard error (warnings,
/// progress) goes to `err` line by line.
InProcessResult RunInProcess(const std::string& tool, const std::vector<std::string>& args,
                             const std::string& command_line, const std::vector<GivenLog>& given,
                             const std::function<void(const std::string&)>& err);

}  // namespace driveid::cli
