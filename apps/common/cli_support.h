// Helpers shared by the command-line tools: exit codes (docs/formats.md#exit-codes), the
// options every fitting subcommand has, and writing its outputs.
#pragma once

#include <cstdio>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "core/errors.h"
#include "core/fit_options.h"
#include "core/fit_result.h"
#include "logs/csv_log.h"
#include "models/parameter_table.h"
#include "report/plot.h"

namespace driveid::cli {

enum ExitCode { kSuccess = 0, kInternal = 1, kUsage = 2, kInvalidInput = 3, kIdentificationFailed = 4 };
/// A gate that failed (`compare` found drift, `validate --fail-below` a low
/// fit): exit 1, like diff, after the command's outputs are complete; the
/// message ("" for none) goes to stderr (docs/formats.md#exit-codes).
constexpr int kGateFailed = 1;
struct GateFailed {
  std::string message;
};

/// Parses the command line and runs `dispatch`, mapping exceptions to exit
/// codes with a one-line message "program: ..." on stderr.
int RunMain(CLI::App& app, int argc, char** argv, const std::function<void()>& dispatch);

/// The exit code, message and (an identification refusal's) parameters of
/// the exception being handled: call inside a catch block. Exceptions not
/// derived from std::exception propagate.
struct Refusal {
  int code;
  std::string message;
  std::vector<std::string> parameters;
};
Refusal CurrentRefusal();

/// Every option that collects a list takes one value per flag (repeat the
/// flag for more), so that `--col a=b log.csv` leaves log.csv positional.
void OneValuePerFlag(CLI::App& app);

/// The exact command line, shell-quoted where needed (for provenance).
std::string CommandLine(int argc, char** argv);

/// Writes `text` to standard output and flushes it; throws OutputError (exit
/// 3) when that fails (a full disk, a closed pipe).
void WriteStdout(const std::string& text);

/// The library names options by their field between marks, ‹free_name›
/// (lib/ holds no flag spelling); the tools print the flag, --free-name.
/// Every text from the library passes through this on its way out
/// (WriteStdout, WriteText, error messages, written parameter files). Pass
/// a large text that is not needed afterwards by std::move: it is then
/// rewritten in place, not copied.
std::string ShowFlags(std::string text);
/// `text` with each control byte but newline and tab (ESC, CR, ...: a file
/// name or a key from a file could move a terminal's cursor or recolour it)
/// written as \xNN. Every message and summary passes through it.
std::string Printable(std::string text);

/// Writes text from the library to a stream (stderr, or stdout for summaries).
void WriteText(std::FILE* stream, const std::string& text);

/// Validators for option values (exit 2 with the option named): a finite
/// number above (or at least) `minimum`, or within [minimum, maximum]; a
/// seed, a whole number 0 .. 2^64 - 1.
CLI::Validator FiniteAbove(double minimum);
CLI::Validator FiniteWithin(double minimum, double maximum);
CLI::Validator FiniteAtLeast(double minimum);
CLI::Validator Seed();
/// --torque-timing: sampled, held, a delay in samples from -1 to 1, and
/// auto (a fit) or file (validate: the fit's, recorded in the file).
CLI::Validator TorqueTimingText(bool file = false);
/// A --plot file name: .png or .svg (report/plot.h, IsSupportedPlotPath).
CLI::Validator PlotPath();

/// Refuses (OptionError, exit 2) an output that is one of the inputs or
/// another output: compared by device and inode where the file exists, by
/// absolute path where it does not. `outputs` pairs an option name with its
/// path ("" = not given); devices such as /dev/null may repeat.
void CheckDistinctFiles(const std::vector<std::string>& inputs,
                        const std::vector<std::pair<std::string, std::string>>& outputs);

/// Output flags every fitting subcommand shares.
struct FitOutputOptions {
  std::string output;  ///< parameter file ("" = stdout)
  std::string trace;   ///< CSV of measured, model, residual
  std::string plot;    ///< PNG or SVG
  bool json = false;
  bool quiet = false;
  bool verbose = false;
  double max_log_gib = 4.0;  ///< --max-log-size: largest log read [GiB]
  bool strict = false;       ///< --strict: adequacy warnings exit 4, nothing written
  double max_seconds = 0.0;  ///< --max-seconds: wall-clock limit of all the command's fits (0: none)
  std::optional<double> fail_below{};  ///< validate --fail-below: exit 1 when a log's fit % is below this
};
/// Adds -o, --trace, --plot, --json, -q, -v, --max-log-size and --strict.
void AddFitOutputOptions(CLI::App& command, FitOutputOptions& options);
/// CheckDistinctFiles for a fit's -o, --trace and --plot.
void CheckFitOutputs(const FitOutputOptions& options, std::vector<std::string> inputs);

/// Everything a fit produces; EmitFitOutputs writes it all or nothing.
struct FitOutputs {
  std::string parameter_file;       ///< YAML text
  std::string trace_csv;            ///< CSV text
  std::vector<PlotPanel> plot_panels;  ///< stacked panels sharing the x axis
  std::string plot_x_label = "time [s]";
  bool plot_log_x = false;
  FitResult fit;
  FitProvenance provenance;
  /// A command's own summary (text or JSON) instead of the fit table, printed
  /// where the table would be (unless quiet), inside the transaction.
  std::optional<std::string> summary;
};

/// Prints the adequacy warnings on stderr (with --strict they end the run:
/// IdentificationError, nothing written), renders the plot, writes trace and
/// parameter file (atomically), and prints the summary (table or JSON) on
/// stdout, or on stderr when the parameter file itself goes to stdout.
void EmitFitOutputs(const FitOutputOptions& options, const FitOutputs& outputs);

/// What a command run in-process (apps/common/in_process.h) writes: its
/// standard output and the outputs of its fits (each EmitFitOutputs call's);
/// its standard error (warnings, progress lines) goes to `err` line by line.
struct StreamCapture {
  std::string out;
  std::vector<FitOutputs> fits;
  std::function<void(const std::string&)> err;
};

/// While it lives, this thread's WriteStdout, WriteText, progress lines and
/// EmitFitOutputs calls go to `capture` as well as (files) or instead of
/// (the standard streams) where the command line sends them.
class CaptureStreams {
 public:
  explicit CaptureStreams(StreamCapture& capture);
  ~CaptureStreams();
  CaptureStreams(const CaptureStreams&) = delete;
  CaptureStreams& operator=(const CaptureStreams&) = delete;

 private:
  StreamCapture* previous_;
};

/// Help text of --free from a model's table: the parameters the fit can
/// estimate (with `extra` names such as a per-log offset) and its default set.
template <class Section, class Model>
std::string FreeOptionHelp(const ParameterTable<Section, Model>& table, const std::string& fit,
                           const std::string& extra = "") {
  std::string names;
  for (const auto& row : table) {
    if (row.spec.InFit(fit)) names += fmt::format("{}{} [{}]", names.empty() ? "" : ", ", row.spec.key, row.spec.unit);
  }
  return fmt::format("parameters to estimate: {}{} (default {})", names, extra,
                     fmt::join(FitParameterKeys(table, fit, true), ","));
}

/// Adds --free NAMES (comma-separated, repeatable) collecting into `free`
/// (which holds the default set until the first --free replaces it);
/// an empty name (`--free ,`, `--free a,,b`) is a CLI::ValidationError (exit 2).
/// How SplitNames treats an empty name ("a,,b", a trailing comma).
enum class EmptyNames { kSkip, kRefuse };
/// The comma-separated names in `text`; kRefuse throws CLI::ValidationError
/// naming `text` for an empty one.
std::vector<std::string> SplitNames(const std::string& text, EmptyNames empty);

void AddFreeOption(CLI::App& command, std::vector<std::string>& free, const std::string& help);

/// With -v, logs every solver iteration of the fit to stderr.
/// -v: every solver iteration on stderr; otherwise a line of progress every
/// 2 s once a fit has run for 2 s. Sets the solver's time limit.
void SetProgress(FitOptions& fit, bool verbose, double max_seconds = 0.0);

}  // namespace driveid::cli
