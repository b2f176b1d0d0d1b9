#include "report/plot.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include "io/atomic_file.h"
#include "io/csv_log.h"

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

std::string TemporaryName(const std::string& base, const std::string& suffix) {
  std::string pattern = base + ".tmp.XXXXXX";
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  const int fd = ::mkstemp(name.data());
  if (fd < 0) throw std::runtime_error(fmt::format("{}: cannot create temporary file", base));
  ::close(fd);
  const std::string created(name.data());
  const std::string renamed = created + suffix;
  if (std::rename(created.c_str(), renamed.c_str()) != 0) {
    std::remove(created.c_str());
    throw std::runtime_error(fmt::format("{}: cannot create temporary file", base));
  }
  return renamed;
}

}  // namespace

bool IsSupportedPlotPath(const std::string& path) {
  const std::string lower = Lower(path);
  return EndsWith(lower, ".png") || EndsWith(lower, ".svg");
}

void RenderFitPlot(const std::string& path, const std::vector<PlotSeries>& series, const PlotLabels& labels) {
  const bool svg = EndsWith(Lower(path), ".svg");
  const std::string image = TemporaryName(path, svg ? ".svg" : ".png");
  const std::string script_path = TemporaryName(path, ".gp");
  const std::string error_path = TemporaryName(path, ".err");
  auto cleanup = [&] {
    std::remove(script_path.c_str());
    std::remove(error_path.c_str());
  };

  std::string script;
  script += svg ? "set terminal svg size 1000,800 dynamic noenhanced font 'sans,11'\n"
                : "set terminal pngcairo size 1000,800 noenhanced font 'sans,10'\n";
  script += fmt::format("set output {}\n", GnuplotString(image));
  for (std::size_t s = 0; s < series.size(); ++s) {
    script += fmt::format("$d{} << EOD\n", s);
    const auto& one = series[s];
    for (std::size_t k = 0; k < one.time.size(); ++k) {
      script += fmt::format("{} {} {} {}\n", one.time[k], one.measured[k], one.model[k], one.measured[k] - one.model[k]);
    }
    script += "EOD\n";
  }
  script += "set multiplot layout 2,1\nset grid\nset key outside below horizontal\n";
  script += "set lmargin 12\nset rmargin 4\n";
  script += fmt::format("set title {}\nset ylabel {}\nunset xlabel\n", GnuplotString(labels.title),
                        GnuplotString(labels.y_label));
  std::string measured_plot = "plot ";
  std::string residual_plot = "plot ";
  for (std::size_t s = 0; s < series.size(); ++s) {
    const std::string name = GnuplotString(series[s].title);
    measured_plot += fmt::format(
        "{}$d{} using 1:2 with points pt 7 ps 0.35 lc rgb '#9a9a9a' title {}.' measured', $d{} using 1:3 with lines "
        "lw 2 lc {} title {}.' model'",
        s ? ", " : "", s, name, s, s + 1, name);
    residual_plot += fmt::format("{}$d{} using 1:4 with lines lc {} title {}", s ? ", " : "", s, s + 1, name);
  }
  script += measured_plot + "\n";
  script += "set title 'residual (measured - model)'\nset xlabel 'time [s]'\n";
  script += fmt::format("set ylabel {}\n", GnuplotString("residual " + labels.y_label));
  script += residual_plot + "\nunset multiplot\nset output\n";
  try {
    WriteFileAtomically(script_path, script);
  } catch (...) {
    cleanup();
    std::remove(image.c_str());
    throw;
  }

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, error_path.c_str(), O_WRONLY | O_TRUNC, 0644);
  std::string program = "gnuplot";
  std::vector<char*> argv = {program.data(), const_cast<char*>(script_path.c_str()), nullptr};
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  int status = 0;
  if (spawned == 0) ::waitpid(pid, &status, 0);
  std::string error_text;
  try {
    error_text = ReadFileToString(error_path);
  } catch (...) {
  }
  cleanup();
  if (spawned != 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::remove(image.c_str());
    if (spawned != 0) throw std::runtime_error("cannot run gnuplot for --plot (install the Debian package gnuplot-nox)");
    std::string first = error_text;
    while (!first.empty() && (first.front() == '\n' || first.front() == ' ')) first.erase(first.begin());
    first = first.substr(0, first.find('\n'));
    throw std::runtime_error(fmt::format("{}: gnuplot failed: {}", path, first));
  }
  if (std::rename(image.c_str(), path.c_str()) != 0) {
    std::remove(image.c_str());
    throw std::runtime_error(fmt::format("{}: cannot write plot", path));
  }
}

}  // namespace driveid
