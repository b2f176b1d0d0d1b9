// The C++ side of the Python module driveid (docs/python.md): each function
// takes the command's options as a dict (keys named as its flags, without
// dashes) and returns what the command computed as plain Python values; the
// package (python/driveid/__init__.py) turns them into objects and raises
// the exceptions. The computation is the command's own function
// (apps/drivetrain_fit/axis_command.h ComputeAxisCommand), so the numbers
// are the command line's to the last bit. The GIL is released while it runs.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "core/errors.h"
#include "drivetrain_fit/axis_command.h"
#include "io/axis_log.h"
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

// Array arguments are refused by name: not a 1-D float array (exit 2 as a
// usage error), a length other than t's, a value that is not finite, a
// time that does not increase (exit 3 as bad input).
std::vector<double> TakeArray(const std::string& name, const py::handle& value, std::size_t length) {
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
  if (length != 0 && n != length) {
    throw Failure{3, name + ": " + std::to_string(n) + " values, t has " + std::to_string(length), {}};
  }
  std::vector<double> out(doubles.data(), doubles.data() + n);
  for (std::size_t k = 0; k < n; ++k) {
    if (!std::isfinite(out[k])) throw Failure{3, name + "[" + std::to_string(k) + "]: not a finite number", {}};
  }
  return out;
}

// A log from arrays, with the columns a command requests ("a|b" one of
// them, "?a" optional) in its order, as the readers would deliver it.
CsvLog ArraysLog(const std::string& name, const py::dict& arrays, const std::vector<std::string>& request) {
  CsvLog log;
  log.path = name;
  const std::size_t length = arrays.contains("t") ? TakeArray("t", arrays["t"], 0).size() : 0;
  for (const std::string& entry : request) {
    const bool optional = !entry.empty() && entry[0] == '?';
    const std::string names = optional ? entry.substr(1) : entry;
    std::vector<std::string> alternatives;
    for (std::size_t at = 0;;) {
      const std::size_t bar = names.find('|', at);
      alternatives.push_back(names.substr(at, bar == std::string::npos ? std::string::npos : bar - at));
      if (bar == std::string::npos) break;
      at = bar + 1;
    }
    std::string chosen;
    for (const std::string& a : alternatives) {
      if (arrays.contains(a) && !arrays[py::str(a)].is_none()) {
        chosen = a;
        break;
      }
    }
    if (chosen.empty() && !optional) throw Failure{3, name + ": no " + names + " array given", {}};
    log.names.push_back(chosen.empty() ? alternatives.front() : chosen);
    log.columns.push_back(chosen.empty() ? std::vector<double>{} : TakeArray(chosen, arrays[py::str(chosen)], length));
  }
  for (std::size_t k = 1; k < log.columns.front().size(); ++k) {
    if (!(log.columns.front()[k] > log.columns.front()[k - 1])) {
      throw Failure{3, name + ": t does not increase at sample " + std::to_string(k + 1), {}};
    }
  }
  return log;
}

std::vector<std::string> Strings(const py::dict& options, const char* key) {
  if (!options.contains(key) || options[key].is_none()) return {};
  return options[key].cast<std::vector<std::string>>();
}

// The command's options from the dict: only the keys given replace the
// command's defaults (those of its option struct, which are the flags').
cli::AxisOptions AxisOptionsOf(const py::dict& o) {
  cli::AxisOptions options;
  options.logs = Strings(o, "logs");
  if (o.contains("params") && !o["params"].is_none()) options.params = o["params"].cast<std::string>();
  if (o.contains("free") && !o["free"].is_none()) options.free = Strings(o, "free");
  if (o.contains("method")) options.method = o["method"].cast<std::string>();
  if (options.method != "auto" && options.method != "idim" && options.method != "oe") {
    throw Failure{2, "method: " + options.method + " not in {auto, idim, oe}", {}};
  }
  if (o.contains("cutoff") && !o["cutoff"].is_none()) {
    options.cutoff = o["cutoff"].cast<double>();
    if (!(options.cutoff > 0.0) || !std::isfinite(options.cutoff)) throw Failure{2, "cutoff: must be a finite number > 0", {}};
  }
  if (o.contains("decimation")) {
    options.decimation = o["decimation"].cast<int>();
    if (options.decimation < 1 || options.decimation > 1000) throw Failure{2, "decimation: must be in [1, 1000]", {}};
  }
  if (o.contains("torque_timing")) {
    options.torque_timing = o["torque_timing"].cast<std::string>();
    const std::string problem = cli::TorqueTimingText()(options.torque_timing);
    if (!problem.empty()) throw Failure{2, "torque_timing: " + problem, {}};
  }
  if (o.contains("linear")) options.linear = o["linear"].cast<bool>();
  options.validate = Strings(o, "validate");
  for (const std::string& c : Strings(o, "col")) options.input.columns.push_back(c);
  if (o.contains("trace") && o["trace"].cast<bool>()) options.output.trace = "python";
  return options;
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

// Runs `compute` without the GIL, mapping the library's errors to the
// command's exit codes (apps/common/cli_support.cc RunMain).
template <class Compute>
auto Guarded(Compute compute) -> decltype(compute()) {
  try {
    py::gil_scoped_release release;
    return compute();
  } catch (const cli::GateFailed& e) {
    throw Failure{1, cli::ShowFlags(e.message), {}};
  } catch (const OptionError& e) {
    throw Failure{2, cli::ShowFlags(e.what()), {}};
  } catch (const InputError& e) {
    throw Failure{3, cli::ShowFlags(e.what()), {}};
  } catch (const OutputError& e) {
    throw Failure{3, cli::ShowFlags(e.what()), {}};
  } catch (const IdentificationError& e) {
    throw Failure{4, cli::ShowFlags(e.what()), e.parameters()};
  }
}

py::dict Failed(const Failure& f) {
  py::dict out;
  out["error"] = py::make_tuple(f.code, f.message, f.parameters);
  return out;
}

py::dict Axis(const py::dict& options, const py::object& arrays, const std::string& name,
              const std::string& command_line) {
  try {
    const cli::AxisOptions axis = AxisOptionsOf(options);
    std::vector<CsvLog> given;
    if (!arrays.is_none()) given.push_back(ArraysLog(name, arrays.cast<py::dict>(), AxisLogColumns()));
    if (given.empty() && axis.logs.empty()) throw Failure{2, "logs: give log paths or arrays (t=, q=, tau=)", {}};
    const cli::AxisCommandResult r = Guarded([&] { return cli::ComputeAxisCommand(axis, command_line, std::move(given)); });
    py::dict out = Estimates(r.outputs.fit);
    out["method"] = r.outputs.provenance.model;
    out["parameter_file"] = cli::ShowFlags(r.outputs.parameter_file);
    std::string table = FormatFitTable(r.outputs.fit, r.outputs.provenance);
    for (const std::string& line : r.summary) table += line + "\n";
    out["table"] = cli::ShowFlags(table);
    out["trace_csv"] = r.outputs.trace_csv;
    return out;
  } catch (const Failure& f) {
    return Failed(f);
  }
}

// The library's own time for the same call (scripts/benchmark: the
// module's overhead is a call's time minus this), median of `repeats`.
double AxisLibrarySeconds(const py::dict& options, const py::dict& arrays, const std::string& name, int repeats) {
  const cli::AxisOptions axis = AxisOptionsOf(options);
  const CsvLog log = ArraysLog(name, arrays, AxisLogColumns());
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
  m.def("axis", &driveid::python::Axis, py::arg("options"), py::arg("arrays"), py::arg("name"), py::arg("command_line"),
        "drivetrain-fit axis: options as a dict, arrays (t, q, tau or i, qd, tau_known) or None");
  m.def("axis_library_seconds", &driveid::python::AxisLibrarySeconds, py::arg("options"), py::arg("arrays"),
        py::arg("name"), py::arg("repeats"), "the library's median time for axis on these arrays (benchmark)");
}
