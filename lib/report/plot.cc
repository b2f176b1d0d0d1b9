#include "report/plot.h"

#include <algorithm>
#include <cerrno>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include "core/errors.h"
#include "system/child_process.h"
#include "system/temporary_files.h"

extern char** environ;

namespace driveid {
namespace {

std::string Lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

bool EndsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// gnuplot string literal in single quotes ('' escapes a quote).
std::string GnuplotString(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') out += "''";
    else if (static_cast<unsigned char>(c) >= 0x20) out += c;
  }
  return out + "'";
}


}  // namespace

std::vector<std::string> LineStyles(const std::vector<PlotLine>& lines) {
  // Colour-blind-safe pairs (full, light tint): blue, orange, green, purple, red, grey.
  static const char* const kFull[] = {"#1f5fa8", "#d9600f", "#238b45", "#6a3d9a", "#c0262d", "#4d4d4d"};
  static const char* const kLight[] = {"#a9c6e8", "#f7c29b", "#a8dcb5", "#cab2d6", "#f2a9ac", "#c4c4c4"};
  constexpr std::size_t kColours = sizeof kFull / sizeof kFull[0];
  std::vector<std::string> out;
  std::size_t channel = 0;
  for (const auto& line : lines) {
    const std::size_t c = channel % kColours;
    if (line.grey) {
      out.push_back("with points pt 7 ps 0.35 lc rgb '#9a9a9a'");
    } else if (line.points) {
      out.push_back(fmt::format("with points pt 7 ps 0.3 lc rgb '{}'", kLight[c]));  // the model follows
    } else if (line.dots) {
      out.push_back(fmt::format("with points pt 7 ps 0.3 lc rgb '{}'", kFull[c]));
      ++channel;
    } else {
      out.push_back(fmt::format("with lines lw 2 lc rgb '{}'", kFull[c]));
      ++channel;
    }
  }
  return out;
}

bool IsSupportedPlotPath(const std::string& path) {
  const std::string lower = Lower(path);
  return EndsWith(lower, ".png") || EndsWith(lower, ".svg");
}

namespace {

// The gnuplot script: the data blocks, then one panel per row.
std::string GnuplotScript(const std::vector<PlotPanel>& panels, const std::string& x_label, bool log_x, bool svg,
                          const std::string& image) {
  const int height = 150 + 330 * static_cast<int>(panels.size());
  std::string script;
  script += svg ? fmt::format("set terminal svg size 1000,{} dynamic noenhanced font 'sans,11'\n", height)
                : fmt::format("set terminal pngcairo size 1000,{} noenhanced font 'sans,10'\n", height);
  script += fmt::format("set output {}\n", GnuplotString(image));
  int block = 0;
  for (const auto& panel : panels) {
    for (const auto& line : panel.lines) {
      script += fmt::format("$d{} << EOD\n", block++);
      for (std::size_t k = 0; k < line.x.size(); ++k) script += fmt::format("{} {}\n", line.x[k], line.y[k]);
      script += "EOD\n";
    }
  }
  script += fmt::format("set multiplot layout {},1\nset grid\nset key outside below horizontal\n", panels.size());
  script += "set lmargin 12\nset rmargin 4\n";
  if (log_x) script += "set logscale x\n";
  block = 0;
  for (std::size_t p = 0; p < panels.size(); ++p) {
    const auto& panel = panels[p];
    script += fmt::format("set title {}\nset ylabel {}\n", GnuplotString(panel.title), GnuplotString(panel.y_label));
    script += panel.y_max > panel.y_min ? fmt::format("set yrange [{}:{}]\n", panel.y_min, panel.y_max)
                                        : std::string("set autoscale y\n");
    if (!panel.own_x_label.empty()) {
      script += fmt::format("set xlabel {}\n{}", GnuplotString(panel.own_x_label),
                            panel.own_log_x ? "set logscale x\n" : "unset logscale x\n");
    } else {
      script += p + 1 == panels.size() ? fmt::format("set xlabel {}\n", GnuplotString(x_label)) : "unset xlabel\n";
      script += log_x ? "set logscale x\n" : "unset logscale x\n";
    }
    std::string plot = "plot ";
    const std::vector<std::string> styles = LineStyles(panel.lines);
    for (std::size_t l = 0; l < panel.lines.size(); ++l) {
      plot += fmt::format("{}$d{} using 1:2 {} title {}", l ? ", " : "", block++, styles[l],
                          GnuplotString(panel.lines[l].title));
    }
    script += plot + "\n";
  }
  script += "unset multiplot\nset output\n";
  return script;
}

// An unnamed file (system/temporary_files.h) that a child reaches as
// /proc/self/fd/N; closed when this object goes.
class UnnamedFile {
 public:
  explicit UnnamedFile(const std::string& what) : fd_(CreateUnnamedFile()) {
    if (fd_ < 0) throw OutputError(fmt::format("{}: cannot create a temporary file: {}", what, std::strerror(errno)));
  }
  ~UnnamedFile() { ::close(fd_); }
  UnnamedFile(const UnnamedFile&) = delete;
  UnnamedFile& operator=(const UnnamedFile&) = delete;
  int fd() const { return fd_; }
  std::string name() const { return fmt::format("/proc/self/fd/{}", fd_); }
  // Everything written to it (by this process or a child), at most `limit` bytes.
  std::string Contents(std::size_t limit) const {
    std::string out;
    std::vector<char> chunk(1 << 16);
    for (off_t at = 0; out.size() <= limit;) {
      const ssize_t n = ::pread(fd_, chunk.data(), chunk.size(), at);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      out.append(chunk.data(), static_cast<std::size_t>(n));
      at += n;
    }
    return out;
  }

 private:
  int fd_;
};

// Runs gnuplot on the script file `script` (standard error to `errors`),
// registered as the writer of the image (killed by a termination signal);
// it starts with no signal blocked and inherits the unnamed files it names
// (a dup2 onto itself clears close-on-exec in the child only). False when it
// could not start; `status` is its wait status.
bool RunGnuplot(const UnnamedFile& script, const UnnamedFile& image, const UnnamedFile& errors, int& status) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, errors.fd(), STDERR_FILENO);
  posix_spawn_file_actions_adddup2(&actions, script.fd(), script.fd());
  posix_spawn_file_actions_adddup2(&actions, image.fd(), image.fd());
  std::string program = "gnuplot";
  std::string script_name = script.name();
  std::vector<char*> argv = {program.data(), script_name.data(), nullptr};
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK);
  pid_t pid = 0;
  int spawned = 0;
  {
    TerminationSignalsBlocked blocked;
    spawned = posix_spawnp(&pid, "gnuplot", &actions, &attributes, argv.data(), environ);
    if (spawned == 0) SetTemporaryFileWriter(pid);
  }
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  if (spawned == 0) {
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    SetTemporaryFileWriter(0);
  }
  return spawned == 0;
}

}  // namespace

std::string RenderPanels(const std::string& path, const std::vector<PlotPanel>& panels, const std::string& x_label,
                         bool log_x) {
  const bool svg = EndsWith(Lower(path), ".svg");
  // gnuplot's script, image and messages go through files without a name:
  // nothing is left behind, whatever ends the run (SIGKILL too).
  const UnnamedFile script_file(path), image(path), errors(path);
  const std::string script = GnuplotScript(panels, x_label, log_x, svg, image.name());
  if (!WriteAll(script_file.fd(), script.data(), script.size())) {
    throw OutputError(fmt::format("{}: cannot write gnuplot's script: {}", path, std::strerror(errno)));
  }
  int status = 0;
  const bool started = RunGnuplot(script_file, image, errors, status);
  if (!started) throw OutputError("cannot run gnuplot for ‹plot› (install the Debian package gnuplot-nox)");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::string first = errors.Contents(1 << 16);
    while (!first.empty() && (first.front() == '\n' || first.front() == ' ')) first.erase(first.begin());
    first = first.substr(0, first.find('\n'));
    throw OutputError(fmt::format("{}: gnuplot failed: {}", path, first));
  }
  constexpr std::size_t kMaxImageBytes = std::size_t{1} << 30;
  std::string bytes = image.Contents(kMaxImageBytes);
  if (bytes.empty()) throw OutputError(fmt::format("{}: gnuplot wrote no image", path));
  if (bytes.size() > kMaxImageBytes) throw OutputError(fmt::format("{}: gnuplot's image exceeds 1 GiB", path));
  return bytes;
}

std::vector<PlotPanel> MakeFitPanels(const std::vector<PlotSeries>& series, const PlotLabels& labels) {
  PlotPanel fit{labels.title, labels.y_label, {}};
  PlotPanel residual{"residual (measured - model)", "residual " + labels.y_label, {}};
  for (const auto& one : series) {
    fit.lines.push_back({one.title + " measured", one.time, one.measured, true});
    fit.lines.push_back({one.title + " model", one.time, one.model, false});
    std::vector<double> difference(one.time.size());
    for (std::size_t k = 0; k < difference.size(); ++k) difference[k] = one.measured[k] - one.model[k];
    residual.lines.push_back({one.title, one.time, std::move(difference), false});
  }
  return {fit, residual};
}

}  // namespace driveid
