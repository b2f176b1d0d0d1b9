#include "common/cli_support.h"

#include <chrono>
#include <memory>

#include <algorithm>

#include <charconv>
#include <condition_variable>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <mutex>
#include <new>
#include <optional>
#include <thread>
#include <filesystem>
#include <system_error>

#include <signal.h>
#include <sys/stat.h>
#include <stdexcept>

#include <fmt/format.h>

#include "core/errors.h"
#include "system/atomic_file.h"
#include "system/temporary_files.h"
#include "report/fit_summary.h"

namespace driveid::cli {
namespace {

thread_local StreamCapture* capture = nullptr;

// A line of the standard error: to the capture's sink when one is set.
void Say(const std::string& text) {
  if (capture != nullptr && capture->err) capture->err(text);
  else std::fputs(text.c_str(), stderr);
}

// One line: newlines in a message become "; ".
std::string OneLine(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  std::string out;
  for (char c : text) {
    if (c == '\n') out += "; ";
    else out += c;
  }
  return out;
}

void Fail(const std::string& program, const std::string& message) {
  std::fprintf(stderr, "%s: %s\n", program.c_str(), Printable(OneLine(ShowFlags(message))).c_str());
}

// SIGINT, SIGTERM, SIGHUP and SIGPIPE (standard output closed by its
// reader, as `| head` does; it arrives while the outputs are staged, since
// standard output is written before they are committed): remove the run's
// temporary files (and stop gnuplot), then die of the signal as if there
// were no handler (exit status 128 + signal in a shell). A signal ignored at
// start (nohup, a background job of a script) stays ignored; an ignored
// SIGPIPE makes the write fail, handled as a full disk is.
void DieOfSignal(int signal_number) {
  RemoveTemporaryFilesNow();
  ::signal(signal_number, SIG_DFL);
  ::raise(signal_number);
}

void InstallSignalCleanup() {
  for (int signal_number : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) {
    struct sigaction previous {};
    if (::sigaction(signal_number, nullptr, &previous) == 0 && previous.sa_handler == SIG_IGN) continue;
    struct sigaction action {};
    action.sa_handler = DieOfSignal;
    sigemptyset(&action.sa_mask);
    for (int other : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) sigaddset(&action.sa_mask, other);
    ::sigaction(signal_number, &action, nullptr);
  }
}

}  // namespace

// Every option of `app` and of its subcommands that collects a list takes
// one value per flag (the flag is repeated for more), so that `--col a=b
// log.csv` leaves log.csv to the positional arguments.
void OneValuePerFlag(CLI::App& app) {
  for (CLI::Option* option :
       app.get_options([](CLI::Option* o) { return o->nonpositional() && o->get_items_expected_max() > 1; })) {
    option->allow_extra_args(false);
  }
  for (CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) OneValuePerFlag(*command);
}


int RunMain(CLI::App& app, int argc, char** argv, const std::function<void()>& dispatch) {
  const std::string program = app.get_name();
  InstallSignalCleanup();
  OneValuePerFlag(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    Fail(program, std::string(e.what()) + " (see --help)");
    return kUsage;
  } catch (const OptionError& e) {  // from an option's callback
    Fail(program, e.what());
    return kUsage;
  }
  try {
    dispatch();
    return kSuccess;
  } catch (...) {
    const Refusal refusal = CurrentRefusal();
    if (!refusal.message.empty()) Fail(program, refusal.message);
    return refusal.code;
  }
}

Refusal CurrentRefusal() {
  try {
    throw;
  } catch (const GateFailed& e) {
    return {kGateFailed, e.message, {}};
  } catch (const InputError& e) {
    return {kInvalidInput, e.what(), {}};
  } catch (const IdentificationError& e) {
    return {kIdentificationFailed, e.what(), e.parameters()};
  } catch (const OutputError& e) {
    return {kInvalidInput, e.what(), {}};
  } catch (const OptionError& e) {
    return {kUsage, e.what(), {}};
  } catch (const std::bad_alloc&) {
    // The input's size met the memory this process may use (ulimit -v, a
    // container's limit): a limit of the machine, not a bug.
    return {kInvalidInput, "out of memory: the inputs need more memory than this process may use (ulimit -v); "
                           "crop or split the logs, or raise the limit", {}};
  } catch (const std::exception& e) {
    return {kInternal, std::string("internal error: ") + e.what(), {}};
  }
}

std::string CommandLine(int argc, char** argv) {
  std::string out;
  for (int i = 0; i < argc; ++i) {
    std::string arg = argv[i];
    if (i == 0) {
      const auto slash = arg.rfind('/');
      if (slash != std::string::npos) arg = arg.substr(slash + 1);
    }
    const bool plain = !arg.empty() && arg.find_first_not_of(
        "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_./=,:+@%") == std::string::npos;
    if (!out.empty()) out += ' ';
    if (plain) {
      out += arg;
    } else {
      out += '\'';
      for (char c : arg) {
        if (c == '\'') out += "'\\''";
        else out += c;
      }
      out += '\'';
    }
  }
  return out;
}

std::string ShowFlags(std::string text) {
  static const std::string open = "\u2039", close = "\u203a";  // the library's marks around a field: ‹field›
  std::size_t at = 0;
  while ((at = text.find(open, at)) != std::string::npos) {
    const std::size_t end = text.find(close, at + open.size());
    if (end == std::string::npos) break;
    std::string flag = "--" + text.substr(at + open.size(), end - at - open.size());
    std::replace(flag.begin(), flag.end(), '_', '-');
    text.replace(at, end + close.size() - at, flag);
    at += flag.size();
  }
  return text;
}

std::string Printable(std::string text) {
  const auto control = [](unsigned char c) { return (c < 0x20 && c != '\n' && c != '\t') || c == 0x7f; };
  if (std::none_of(text.begin(), text.end(), [&](char c) { return control(static_cast<unsigned char>(c)); })) {
    return text;
  }
  std::string out;
  out.reserve(text.size() + 16);
  for (char c : text) {
    if (control(static_cast<unsigned char>(c))) out += fmt::format("\\x{:02x}", static_cast<unsigned char>(c));
    else out += c;
  }
  return out;
}

void WriteText(std::FILE* stream, const std::string& text) {
  std::string shown = Printable(ShowFlags(text));
  if (capture == nullptr) std::fputs(shown.c_str(), stream);
  else if (stream == stdout) capture->out += shown;
  else Say(shown);
}

CaptureStreams::CaptureStreams(StreamCapture& into) : previous_(capture) { capture = &into; }
CaptureStreams::~CaptureStreams() { capture = previous_; }

void WriteStdout(const std::string& text) {
  // A simulated log can be hundreds of MB: copied only when it holds a mark.
  std::string shown;
  const bool marked = text.find("\u2039") != std::string::npos;
  const bool control = std::any_of(text.begin(), text.end(), [](char c) {
    const auto b = static_cast<unsigned char>(c);
    return (b < 0x20 && b != '\n' && b != '\t') || b == 0x7f;
  });
  if (marked || control) shown = Printable(marked ? ShowFlags(text) : text);
  const std::string& out = marked || control ? shown : text;
  if (capture != nullptr) {
    capture->out += out;
    return;
  }
  if (std::fwrite(out.data(), 1, out.size(), stdout) != out.size() || std::fflush(stdout) != 0 ||
      std::ferror(stdout)) {
    throw OutputError("standard output: write error");
  }
}

namespace {

// The number an option value holds, or nullopt when it is not one (whole text).
std::optional<double> ParseDouble(const std::string& text) {
  double value = 0.0;
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  if (begin != end && *begin == '+') ++begin;
  const auto result = std::from_chars(begin, end, value);
  if (result.ec != std::errc() || result.ptr != end) return std::nullopt;
  return value;
}

}  // namespace

std::vector<std::string> SplitNames(const std::string& text, EmptyNames empty) {
  std::vector<std::string> names;
  std::size_t begin = 0;
  while (true) {
    const std::size_t end = text.find(',', begin);
    const std::string name = text.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
    if (!name.empty()) {
      names.push_back(name);
    } else if (empty == EmptyNames::kRefuse) {
      throw CLI::ValidationError(fmt::format("'{}' holds an empty parameter name", text));
    }
    if (end == std::string::npos) return names;
    begin = end + 1;
  }
}

void AddFreeOption(CLI::App& command, std::vector<std::string>& free, const std::string& help) {
  command
      .add_option_function<std::vector<std::string>>(
          "--free",
          [&free](const std::vector<std::string>& texts) {
            free.clear();  // given: replaces the default set
            for (const std::string& text : texts) {
              try {
                for (auto& name : SplitNames(text, EmptyNames::kRefuse)) free.push_back(std::move(name));
              } catch (const CLI::ValidationError& e) {
                throw CLI::ValidationError("--free", e.what());
              }
            }
          },
          help)
      ->type_name("NAMES")
      ->expected(1)
      ->allow_extra_args(false)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

CLI::Validator FiniteWithin(double minimum, double maximum) {
  return CLI::Validator(
      [minimum, maximum](std::string& text) -> std::string {
        const auto value = ParseDouble(text);
        if (value && *value >= minimum && *value <= maximum) return {};  // NaN fails both
        return fmt::format("{}: must be a number in [{}, {}]", text, minimum, maximum);
      },
      fmt::format("NUMBER in [{}, {}]", minimum, maximum));
}

CLI::Validator FiniteAbove(double minimum) {
  return CLI::Validator(
      [minimum](std::string& text) -> std::string {
        const auto value = ParseDouble(text);
        if (value && std::isfinite(*value) && *value > minimum) return {};
        return fmt::format("{}: must be a finite number > {}", text, minimum);
      },
      fmt::format("NUMBER > {}", minimum));
}

CLI::Validator FiniteAtLeast(double minimum) {
  return CLI::Validator(
      [minimum](std::string& text) -> std::string {
        const auto value = ParseDouble(text);
        if (value && std::isfinite(*value) && *value >= minimum) return {};
        return fmt::format("{}: must be a finite number >= {}", text, minimum);
      },
      fmt::format("NUMBER >= {}", minimum));
}

CLI::Validator Seed() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::uint64_t value = 0;
        const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
        if (result.ec == std::errc() && result.ptr == text.data() + text.size()) return {};
        return fmt::format("{}: a seed is a whole number from 0 to {}", text, std::numeric_limits<std::uint64_t>::max());
      },
      "SEED");
}

CLI::Validator TorqueTimingText(bool file) {
  return CLI::Validator(
      [file](std::string& text) -> std::string {
        if (text == "sampled" || text == "held" || (file ? text == "file" : text == "auto")) return {};
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (!text.empty() && end == text.c_str() + text.size() && std::abs(value) <= 1.0) return {};
        return fmt::format("{}: {}sampled, held or a delay in samples from -1 to 1", text, file ? "file, " : "auto, ");
      },
      file ? "file|sampled|held|D" : "auto|sampled|held|D");
}

namespace {

// Identity of a file: device and inode if it exists, else its absolute path.
struct FileIdentity {
  bool exists = false;
  bool regular = true;
  dev_t device = 0;
  ino_t inode = 0;
  std::string absolute;
  bool operator==(const FileIdentity& other) const {
    if (exists != other.exists) return false;
    return exists ? device == other.device && inode == other.inode : absolute == other.absolute;
  }
};

FileIdentity IdentityOf(const std::string& path) {
  FileIdentity id;
  struct stat status {};
  if (::stat(path.c_str(), &status) == 0) {
    id.exists = true;
    id.regular = S_ISREG(status.st_mode);
    id.device = status.st_dev;
    id.inode = status.st_ino;
  } else {
    std::error_code error;
    id.absolute = std::filesystem::weakly_canonical(std::filesystem::absolute(path, error), error).string();
  }
  return id;
}

}  // namespace

void CheckDistinctFiles(const std::vector<std::string>& inputs,
                        const std::vector<std::pair<std::string, std::string>>& outputs) {
  std::vector<std::pair<std::string, FileIdentity>> seen;  // option or "input", identity
  for (const auto& input : inputs) {
    if (!input.empty()) seen.emplace_back(input, IdentityOf(input));
  }
  const std::size_t input_count = seen.size();
  for (const auto& [option, path] : outputs) {
    if (path.empty()) continue;
    const FileIdentity id = IdentityOf(path);
    for (std::size_t i = 0; i < seen.size(); ++i) {
      if (!(seen[i].second == id)) continue;
      if (i < input_count) {
        throw OptionError(fmt::format("{} {}: is an input of this run ({}); it would be overwritten", option, path,
                                      seen[i].first));
      }
      if (id.regular) {
        throw OptionError(fmt::format("{} {}: the same file as {}", option, path, seen[i].first));
      }
    }
    seen.emplace_back(option + " " + path, id);
  }
}

CLI::Validator PlotPath() {
  return CLI::Validator(
      [](std::string& path) {
        return IsSupportedPlotPath(path) ? std::string() : std::string("--plot needs a .png or .svg file name");
      },
      "", "PlotPath");
}

void CheckFitOutputs(const FitOutputOptions& options, std::vector<std::string> inputs) {
  CheckDistinctFiles(inputs, {{"-o", options.output}, {"--trace", options.trace}, {"--plot", options.plot}});
}

void AddFitOutputOptions(CLI::App& command, FitOutputOptions& options) {
  command.add_option("-o,--output", options.output, "write the fitted parameter file here (default: stdout)");
  command.add_option("--trace", options.trace, "write a CSV of time, measured, model and residual per channel");
  command.add_option("--plot", options.plot, "render fit vs measurement and residuals (.png or .svg)")
      ->check(PlotPath());
  command.add_flag("--json", options.json, "print the summary as one JSON object instead of the table");
  command.add_flag("-q,--quiet", options.quiet, "print no summary table");
  command.add_flag("-v,--verbose", options.verbose, "log solver iterations on stderr");
  command
      .add_option("--max-log-size", options.max_log_gib,
                  "largest log to read [GiB]; a fit holds about 3 times its logs' size in memory")
      ->capture_default_str()
      ->check(FiniteWithin(1e-6, 1024.0));
  command.add_option("--max-seconds", options.max_seconds,
                     "wall-clock limit of all the command's fits together [s]: reached, a fit ends at its best point "
                     "with a warning, and one that would start after it is refused naming the limit (0: none)")
      ->capture_default_str()
      ->check(FiniteWithin(0.0, 1e6));
  command.add_flag("--strict", options.strict,
                   "adequacy warnings (docs/models.md#adequacy) fail the run: exit 4, nothing written");
}

void EmitFitOutputs(const FitOutputOptions& options, const FitOutputs& outputs) {
  if (options.strict && !outputs.fit.warnings.empty()) {
    throw IdentificationError(fmt::format("--strict: {} adequacy warning{}; nothing written: {}",
                                          outputs.fit.warnings.size(), outputs.fit.warnings.size() > 1 ? "s" : "",
                                          fmt::join(outputs.fit.warnings, "; ")));
  }
  if (capture != nullptr) capture->fits.push_back(outputs);
  // On stderr once: the summary table lists them when it goes there itself.
  const bool table_on_stderr = options.output.empty() && !options.quiet && !options.json;
  if (!table_on_stderr) {
    for (const auto& w : outputs.fit.warnings) WriteText(stderr, "warning: " + w + "\n");
  }
  // All or nothing: render the plot, then write every file together.
  std::vector<std::pair<std::string, std::string>> files;
  if (!options.plot.empty()) files.emplace_back(options.plot, RenderPanels(options.plot, outputs.plot_panels, outputs.plot_x_label, outputs.plot_log_x));
  if (!options.trace.empty()) files.emplace_back(options.trace, outputs.trace_csv);
  if (!options.output.empty()) files.emplace_back(options.output, ShowFlags(outputs.parameter_file));
  // The summary and standard output belong to the transaction: a full disk
  // or a closed pipe there leaves the files as they were.
  WriteFilesAtomically(files, [&] {
    const bool summary_on_stdout = !options.output.empty();
    std::string summary;
    if (outputs.summary) summary = options.quiet && !options.json ? "" : *outputs.summary;
    else if (options.json) summary = DumpJson(FitJson(outputs.fit, outputs.provenance));
    else if (!options.quiet) summary = FormatFitTable(outputs.fit, outputs.provenance);
    // --json: exactly one JSON object on stdout (docs/formats.md#json-summaries);
    // without -o the parameter file is then not written anywhere.
    if (options.json) {
      WriteStdout(summary);
      return;
    }
    if (!summary_on_stdout) WriteText(stderr, summary);
    WriteStdout(summary_on_stdout ? summary : outputs.parameter_file);
  });
}

namespace {

// A line on stderr at least every kHeartbeatSeconds while a fit runs, also
// inside one long evaluation (a multi-log output-error simulation), from a
// thread of its own; the iteration lines count as lines. Started at the
// first fit, stopped and joined at exit.
constexpr double kHeartbeatSeconds = 5.0;

class Heartbeat {
 public:
  ~Heartbeat() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
  }
  void Running(bool on) {
    const std::lock_guard<std::mutex> lock(mutex_);
    active_ += on ? 1 : -1;
    // A run that starts when none runs starts the clock (the Python module
    // runs one command after another in one process).
    if (on && active_ == 1) start_ = last_line_ = MonotonicSeconds();
    if (!thread_.joinable()) thread_ = std::thread([this] { Loop(); });
  }
  /// A line was printed (an iteration's); `iteration`, `cost` for the next beat.
  void Said(int iteration, double cost) {
    const std::lock_guard<std::mutex> lock(mutex_);
    last_line_ = MonotonicSeconds();
    iteration_ = iteration;
    cost_ = cost;
  }
  void Saw(int iteration, double cost) {
    const std::lock_guard<std::mutex> lock(mutex_);
    iteration_ = iteration;
    cost_ = cost;
  }

 private:
  void Loop() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stop_) {
      wake_.wait_for(lock, std::chrono::milliseconds(500));
      const double now = MonotonicSeconds();
      if (stop_ || active_ <= 0 || now - last_line_ < kHeartbeatSeconds) continue;
      last_line_ = now;
      std::fprintf(stderr, "fitting: %.0f s, iteration %d, cost %.6e (evaluating)\n", now - start_, iteration_, cost_);
    }
  }
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread thread_;
  bool stop_ = false;
  int active_ = 0, iteration_ = 0;
  double start_ = 0.0, last_line_ = 0.0, cost_ = 0.0;
};

Heartbeat& TheHeartbeat() {
  static Heartbeat heartbeat;
  return heartbeat;
}

}  // namespace

void SetProgress(FitOptions& fit, bool verbose, double max_seconds) {
  fit.max_seconds = max_seconds;
  // --max-seconds bounds the command's every fit together: from here on.
  fit.deadline = max_seconds > 0.0 ? MonotonicSeconds() + max_seconds : 0.0;
  fit.running = [](bool on) { TheHeartbeat().Running(on); };
  if (verbose) {
    fit.progress = [](const FitIteration& it) {
      Say(fmt::format("iteration {:3d}  cost {:.9e}  |gradient| {:.3e}  |step| {:.3e}\n", it.iteration, it.cost,
                      it.gradient_norm, it.step_norm));
      TheHeartbeat().Said(it.iteration, it.cost);
    };
    return;
  }
  // A long fit says it is alive: a line every 2 s after the first 2 s (and
  // the heartbeat's every 5 s inside a long evaluation).
  auto next = std::make_shared<double>(2.0);
  const double begin = MonotonicSeconds();
  fit.progress = [next, begin](const FitIteration& it) {
    const double elapsed = MonotonicSeconds() - begin;
    if (elapsed < *next) {
      TheHeartbeat().Saw(it.iteration, it.cost);
      return;
    }
    *next = elapsed + 2.0;
    Say(fmt::format("fitting: {:.0f} s, iteration {}, cost {:.6e}\n", elapsed, it.iteration, it.cost));
    TheHeartbeat().Said(it.iteration, it.cost);
  };
}

}  // namespace driveid::cli
