// The C++ side of the Python module driveid (docs/python.md): `run` runs a
// command of the tools in-process (apps/common/in_process.h) from the
// arguments the package (python/driveid/__init__.py) makes of its keyword
// arguments, with numpy arrays as logs in memory, and returns what the
// command printed and its fits' outputs as plain Python values; the package
// turns them into objects and raises the exceptions. The parsing, checks
// and computation are the command's own, so the numbers are the command
// line's to the last bit. The GIL is released while it runs.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "common/in_process.h"
#include "core/errors.h"
#include "drivetrain_fit/axis_command.h"
#include "logs/axis_log.h"
#include "report/fit_summary.h"

namespace py = pybind11;

namespace driveid::python {
namespace {

// A refusal the package raises as its exception class (docs/python.md#errors):
// the exit code the command would return and the command's message.
struct Failure {
  int code;
  std::string message;
  std::vector<std::string> parameters;
};

// An array argument, refused by name when it is not a 1-D float array
// (exit 2 as a usage error) or holds a value that is not finite (exit 3 as
// bad input); GivenLogs checks the lengths, the reader the time's order.
std::vector<double> TakeArray(const std::string& name, const py::handle& value) {
  if (!py::isinstance<py::array>(value)) {
    throw Failure{2, name + ": expected a numpy float array (numpy.asarray(x, dtype=float))", {}};
  }
  const auto array = py::reinterpret_borrow<py::array>(value);
  if (array.dtype().kind() != 'f') {
    throw Failure{2, name + ": expected floats, got dtype " + std::string(py::str(array.dtype())), {}};
  }
  if (array.ndim() != 1) throw Failure{2, name + ": expected a 1-D array", {}};
  const auto doubles = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  const auto n = static_cast<std::size_t>(doubles.size());
  std::vector<double> out(doubles.data(), doubles.data() + n);
  for (std::size_t k = 0; k < n; ++k) {
    if (!std::isfinite(out[k])) throw Failure{3, name + "[" + std::to_string(k) + "]: not a finite number", {}};
  }
  return out;
}

py::dict Estimates(const FitResult& fit) {
  py::list estimates;
  for (const ParameterEstimate& e : fit.estimates) {
    py::dict d;
    d["name"] = e.name;
    d["value"] = e.value;
    d["std"] = e.standard_error;
    d["ci95"] = py::make_tuple(e.ci95_low, e.ci95_high);
    d["unit"] = e.unit;
    estimates.append(d);
  }
  py::list channels;
  for (const ChannelStatistics& c : fit.channels) {
    py::dict d;
    d["name"] = c.name;
    d["samples"] = c.samples;
    d["rmse"] = c.rmse;
    d["fit_percent"] = c.fit_percent;
    d["relative_error_percent"] = c.relative_error_percent;
    d["lag1"] = c.autocorrelation;
    d["inflation"] = c.inflation;
    channels.append(d);
  }
  py::dict out;
  out["estimates"] = estimates;
  out["covariance"] = fit.covariance;
  out["correlation"] = fit.correlation;
  out["statistics"] = channels;
  std::vector<std::string> warnings, notes;
  for (const std::string& w : fit.warnings) warnings.push_back(cli::ShowFlags(w));
  for (const std::string& n : fit.notes) notes.push_back(cli::ShowFlags(n));
  out["warnings"] = warnings;
  out["notes"] = notes;
  return out;
}

py::dict Failed(const Failure& f) {
  py::dict out;
  out["error"] = py::make_tuple(f.code, f.message, f.parameters);
  return out;
}

// One fit's outputs as the package's Fit takes them (the table as the
// command prints it, its own summary where it has one).
py::dict FitDict(const cli::FitOutputs& outputs) {
  py::dict out = Estimates(outputs.fit);
  out["method"] = outputs.provenance.model;
  out["parameter_file"] = cli::ShowFlags(outputs.parameter_file);
  out["table"] = cli::ShowFlags(outputs.summary ? *outputs.summary : FormatFitTable(outputs.fit, outputs.provenance));
  out["trace_csv"] = outputs.trace_csv;
  return out;
}

// Logs in memory: [(name, {column: array})], each column checked by name.
std::vector<cli::GivenLog> GivenLogs(const py::object& logs) {
  std::vector<cli::GivenLog> given;
  if (logs.is_none()) return given;
  for (const py::handle& entry : logs.cast<py::list>()) {
    const auto pair = entry.cast<py::tuple>();
    cli::GivenLog log;
    log.name = pair[0].cast<std::string>();
    for (const auto& [key, value] : pair[1].cast<py::dict>()) {
      log.names.push_back(key.cast<std::string>());
      log.columns.push_back(TakeArray(log.names.back(), value));
    }
    // Every column as long as t (or, without t, as the first).
    const auto t = std::find(log.names.begin(), log.names.end(), "t");
    const std::size_t reference = t == log.names.end() ? 0 : static_cast<std::size_t>(t - log.names.begin());
    for (std::size_t k = 0; k < log.columns.size(); ++k) {
      const std::size_t n = log.columns[k].size(), length = log.columns[reference].size();
      if (n != length) {
        throw Failure{3, log.names[k] + ": " + std::to_string(n) + " values, " + log.names[reference] + " has " +
                             std::to_string(length), {}};
      }
    }
    given.push_back(std::move(log));
  }
  return given;
}

// Runs `tool args` in-process (apps/common/in_process.h) without the GIL:
// {code, message, parameters, out, fits}. Standard error goes to
// `progress(line)` when it is callable, else to this process's stderr.
py::dict Run(const std::string& tool, const std::vector<std::string>& args, const std::string& command_line,
             const py::object& logs, const py::object& progress) {
  cli::InProcessResult r;
  try {
    const std::vector<cli::GivenLog> given = GivenLogs(logs);
    std::function<void(const std::string&)> err;
    if (!progress.is_none()) {
      // By address: copying a Python object needs the GIL, and the function
      // is copied where the GIL is released.
      const py::object* callback = &progress;
      err = [callback](const std::string& line) {
        py::gil_scoped_acquire gil;
        try {
          (*callback)(line);
        } catch (py::error_already_set& e) {
          e.discard_as_unraisable("driveid progress callback");
        }
      };
    }
    py::gil_scoped_release release;
    r = cli::RunInProcess(tool, args, command_line, given, err);
  } catch (const Failure& f) {
    return Failed(f);
  }
  py::dict out;
  if (r.code != cli::kSuccess) out["error"] = py::make_tuple(r.code, r.message, r.parameters);
  out["out"] = py::bytes(r.out);
  py::list fits;
  for (const cli::FitOutputs& fit : r.fits) fits.append(FitDict(fit));
  out["fits"] = fits;
  return out;
}

// The library's own time for `axis ARGS` on the given log (scripts/benchmark:
// the module's overhead is a call's time minus this), median of `repeats`:
// ComputeAxisCommand on the log already read, as the command calls it.
double AxisLibrarySeconds(const std::vector<std::string>& args, const py::object& logs, int repeats) {
  const std::vector<cli::GivenLog> given = GivenLogs(logs);
  cli::AxisOptions axis;
  CLI::App app;
  cli::SetupAxisCommand(app, axis);
  std::vector<std::string> reversed(args.rbegin(), args.rend());
  app.parse(reversed);
  std::vector<DataFileRecord> records;
  CsvLog log;
  const cli::GivenLogsScope scope(given);
  cli::ReadGivenLog(given.at(0).name, AxisLogColumns(), cli::MakeLogInputOptions(axis.input), records,
                    [&](CsvLog csv) { log = std::move(csv); });
  std::vector<double> seconds;
  py::gil_scoped_release release;
  for (int k = 0; k < std::max(1, repeats); ++k) {
    const auto start = std::chrono::steady_clock::now();
    cli::ComputeAxisCommand(axis, "driveid.axis", {log});
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::nth_element(seconds.begin(), seconds.begin() + static_cast<long>(seconds.size() / 2), seconds.end());
  return seconds[seconds.size() / 2];
}

}  // namespace
}  // namespace driveid::python

PYBIND11_MODULE(_driveid, m) {
  m.doc() = "driveid's C++ side; use the package driveid (docs/python.md)";
  m.attr("version") = DRIVEID_VERSION;
  m.def("run", &driveid::python::Run, py::arg("tool"), py::arg("args"), py::arg("command_line"), py::arg("logs"),
        py::arg("progress"), "a command in-process: its code, message, standard output and fits");
  m.def("axis_library_seconds", &driveid::python::AxisLibrarySeconds, py::arg("args"), py::arg("logs"),
        py::arg("repeats"), "the library's median time for axis ARGS on the given log (benchmark)");
}
