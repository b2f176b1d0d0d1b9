"""driveid from Python: the command line's fits as functions (docs/python.md).

Each function takes keyword arguments named as the command's flags
(``--torque-timing`` is ``torque_timing=``) and computes exactly what the
command computes (the same C++ function), so the numbers are the command
line's to the last bit. Inputs are log paths (read by the same readers:
CSV, MAT, SysId JSON, .wpilog, ROS bags, MCAP), numpy float arrays
(``t=``, ``q=``, ``tau=``, ...), or a DataFrame or dict of columns
(``data=df, col={"t": "time", ...}``). Refusals raise exceptions that
mirror the command's exit codes.

Each function runs its command in-process (the same parsing, checks and
computation as the tool, apps/common/in_process.h), with its outputs
captured rather than printed.
"""

import json
import os
import shlex
import tempfile

from . import _driveid

__version__ = _driveid.version
__all__ = ["axis", "joint", "step", "frf", "robot", "cdrive_friction", "cdrive_inertia", "cdrive_validate",
           "cdrive_simulate", "validate", "gains", "design_axis", "design_joint", "design_robot", "compare", "report",
           "export", "simulate_axis", "simulate_step", "simulate_joint", "simulate_robot", "Fit", "Estimate", "Result",
           "Error", "UsageError", "InputError", "IdentificationError", "GateFailed"]


class Error(Exception):
    """A refusal of driveid; ``exit_code`` is the command line's."""

    exit_code = 1


class GateFailed(Error):
    """A gate (drift, report --gate) failed: exit 1."""

    exit_code = 1


class UsageError(Error, ValueError):
    """An option the command refuses: exit 2."""

    exit_code = 2


class InputError(Error):
    """Input that cannot be read or used, named with its file or argument: exit 3."""

    exit_code = 3


class IdentificationError(Error):
    """The data do not determine the parameters (``parameters`` names them): exit 4."""

    exit_code = 4

    def __init__(self, message, parameters=()):
        super().__init__(message)
        self.parameters = list(parameters)


_ERRORS = {1: GateFailed, 2: UsageError, 3: InputError, 4: IdentificationError}


def _raise(error):
    code, message, parameters = error
    if code == 4:
        raise IdentificationError(message, parameters)
    raise _ERRORS.get(code, Error)(message)


class Estimate(tuple):
    """One estimate: value, std, 95 % interval (low, high) and unit."""

    __slots__ = ()

    def __new__(cls, value, std, ci95, unit):
        return tuple.__new__(cls, (value, std, ci95, unit))

    value = property(lambda self: self[0])
    std = property(lambda self: self[1])
    ci95 = property(lambda self: self[2])
    unit = property(lambda self: self[3])

    def __repr__(self):
        return "Estimate(value=%r, std=%r, ci95=%r, unit=%r)" % tuple(self)


class Fit:
    """A fit's result, as the command reports it.

    ``estimates`` (name -> Estimate), ``names``, ``covariance`` and
    ``correlation`` (numpy, in ``names``' order), ``warnings``, ``notes``,
    ``method`` (the model), ``statistics`` (per channel: samples, rmse,
    fit_percent, relative_error_percent, lag1, inflation), ``trace`` (a
    dict of numpy arrays: time, measured, model, residual, or None),
    ``to_yaml(path)`` writes the parameter file ``-o`` writes,
    ``to_dict()``; ``repr`` is the command's table.
    """

    def __init__(self, raw):
        self._raw = raw
        self.names = [e["name"] for e in raw["estimates"]]
        self.estimates = {e["name"]: Estimate(e["value"], e["std"], tuple(e["ci95"]), e["unit"]) for e in raw["estimates"]}
        self.warnings = list(raw["warnings"])
        self.notes = list(raw["notes"])
        self.method = raw["method"]
        self.statistics = [dict(c) for c in raw["statistics"]]
        self.parameter_file = raw["parameter_file"]
        self._trace = None

    @property
    def covariance(self):
        return self._matrix("covariance")

    @property
    def correlation(self):
        return self._matrix("correlation")

    def _matrix(self, key):
        import numpy  # imported where used: `import driveid` stays fast

        n = len(self.names)
        return numpy.array(self._raw[key], dtype=float).reshape(n, n) if n else numpy.zeros((0, 0))

    @property
    def trace(self):
        """The trace the command's ``--trace`` writes, as numpy arrays per column (None without trace=True)."""
        text = self._raw.get("trace_csv", "")
        if not text:
            return None
        if self._trace is None:
            self._trace = _csv_columns(text)
        return self._trace

    def to_yaml(self, path):
        """Writes the parameter file atomically (a regular file or a new one; never renamed over anything else)."""
        _write_atomically(path, self.parameter_file)

    def to_dict(self):
        return {
            "estimates": {n: {"value": e.value, "std": e.std, "ci95": list(e.ci95), "unit": e.unit} for n, e in self.estimates.items()},
            "names": list(self.names),
            "covariance": list(self._raw["covariance"]),
            "correlation": list(self._raw["correlation"]),
            "warnings": list(self.warnings),
            "notes": list(self.notes),
            "method": self.method,
            "statistics": [dict(c) for c in self.statistics],
        }

    def __repr__(self):
        return self._raw["table"]


def _paths(value):
    if value is None:
        return []
    if isinstance(value, (str, os.PathLike)):
        return [os.fspath(value)]
    return [os.fspath(v) for v in value]


class _Params:
    """params=: a path as given, or a dict written as a temporary parameter file (JSON is YAML)."""

    def __init__(self, params):
        self.path = None
        self._temporary = None
        if params is None:
            return
        if isinstance(params, dict):
            fd, self._temporary = tempfile.mkstemp(prefix="driveid-params-", suffix=".yaml")
            with os.fdopen(fd, "w", encoding="utf-8") as f:
                json.dump(params, f)
            self.path = self._temporary
        else:
            self.path = os.fspath(params)

    def __enter__(self):
        return self.path

    def __exit__(self, *exc):
        if self._temporary:
            os.unlink(self._temporary)


# --- the commands, run in-process -------------------------------------------


class Result:
    """What a command that fits nothing computed (gains, design, validate, compare, report, export, simulate).

    ``text`` is what the command prints (``repr`` shows it); ``data`` its
    ``--json`` summary (json=True; validate's by default) or, for gains, the
    parameter file it writes read as a dict; ``log`` the CSV it writes as
    numpy arrays per column (simulate: the log; design: the reference); ``parameter_file`` the text ``-o`` writes (None if it
    writes none); ``to_yaml(path)`` writes it; ``to_dict()`` is ``data``.
    """

    def __init__(self, command, text, data, parameter_file, warnings):
        self.command = command
        self.text = text
        self.data = data
        self.parameter_file = parameter_file
        self.warnings = warnings
        self._log = None

    @property
    def log(self):
        if self._log is None and self.parameter_file is not None and self.command.startswith(("simulate", "cdrive_sim", "design")):
            self._log = _csv_columns(self.parameter_file)
        return self._log

    def to_yaml(self, path):
        """Writes the file the command's -o writes (a parameter file, a log, a reference, an export) atomically."""
        if self.parameter_file is None:
            raise UsageError("%s writes no file" % self.command)
        _write_atomically(path, self.parameter_file)

    save = to_yaml

    def to_dict(self):
        return self.data

    def __repr__(self):
        return self.text


class Gains(Result):
    """``gains``: the feedback section (``data["feedback"]``) and the command's table."""


class Design(Result):
    """``design ...``: the designed excitation's parameter file and the command's table."""


class Validation(Result):
    """``validate``: per-log fit %, RMSE and lag-1 (``data`` is the command's JSON summary; ``repr`` a table of it)."""

    def __repr__(self):
        if not isinstance(self.data, dict) or "logs" not in self.data:
            return self.text
        lines = ["%s" % self.data.get("model", ""), "%-40s %8s %10s %12s %8s" % ("log", "samples", "fit %", "RMSE", "lag-1")]
        for log in self.data["logs"]:
            lines.append("%-40s %8s %10.3f %12.4g %8.3f" % (log.get("log", ""), log.get("samples", ""),
                                                           log.get("fit_percent") or float("nan"),
                                                           log.get("rmse") or float("nan"),
                                                           log.get("autocorrelation") or float("nan")))
        return "\n".join(lines) + "\n"


def _csv_columns(text):
    import numpy

    lines = [line for line in text.splitlines() if line and not line.startswith("#")]
    if not lines:
        return {}
    header = lines[0].split(",")
    rows = [line.split(",") for line in lines[1:]]
    out = {}
    for k, name in enumerate(header):
        column = [row[k] if k < len(row) else "" for row in rows]
        try:
            out[name] = numpy.array(column, dtype=float)
        except ValueError:
            out[name] = numpy.array(column)
    return out


def _write_atomically(path, text):
    path = os.fspath(path)
    if os.path.lexists(path) and not os.path.isfile(path):
        raise InputError("%s: not a regular file: it is not written over" % path)  # nor renamed over
    fd, temporary = tempfile.mkstemp(prefix=".driveid-", dir=os.path.dirname(os.path.abspath(path)))
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
        os.replace(temporary, path)
    except BaseException:
        os.unlink(temporary)
        raise


def _is_array(value):
    return hasattr(value, "__array__") and not isinstance(value, (str, bytes))


def _flag_words(key, value):
    key = key.rstrip("_") or key  # from_= is --from (Python reserves from)
    flag = ("-" if len(key) == 1 else "--") + key.replace("_", "-")
    if value is None or value is False:
        return []
    if value is True:
        return [flag]
    if isinstance(value, (list, tuple)):
        words = []
        for v in value:
            words += [flag, os.fspath(v) if isinstance(v, os.PathLike) else str(v)]
        return words
    return [flag, os.fspath(value) if isinstance(value, os.PathLike) else str(value)]


def _frame_columns(data):
    """Every numeric column of a DataFrame or mapping, as float arrays under its own name."""
    import numpy

    out = {}
    keys = list(data.columns) if hasattr(data, "columns") else list(data.keys())
    for key in keys:
        column = data[key]
        column = column.to_numpy() if hasattr(column, "to_numpy") else numpy.asarray(column)
        if column.dtype.kind in "iuf" and column.ndim == 1:
            out[str(key)] = numpy.ascontiguousarray(column, dtype=float)
    return out


class _Scratch:
    """A temporary folder for outputs made only when one is asked for (a call's overhead stays small)."""

    def __init__(self):
        self._folder = None

    def path(self, name):
        if self._folder is None:
            self._folder = tempfile.TemporaryDirectory(prefix="driveid-")
        return os.path.join(self._folder.name, name)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        if self._folder is not None:
            self._folder.cleanup()


def _run_command(function, tool, words, kind, logs, kwargs, progress):
    """Runs ``tool words... ARGS`` in-process; ``kind``: fit, result, gains, design, validation, simulate."""
    kwargs = dict(kwargs)
    name = kwargs.pop("name", "arrays")
    data = kwargs.pop("data", None)
    col = kwargs.pop("col", None)
    params = kwargs.pop("params", None)
    trace = kwargs.get("trace")
    if trace is True or trace is False:
        kwargs.pop("trace")
    paths = _paths(logs)
    arrays = {k: kwargs.pop(k) for k in [k for k, v in kwargs.items() if _is_array(v)]}
    given = None
    if data is not None or arrays:
        if data is not None and arrays:
            raise UsageError("data: give data= or arrays, not both")
        if paths:
            raise UsageError("logs: give log paths or arrays, not both")
        given = [(name, arrays if data is None else _frame_columns(data))]
        paths = [name]
        length = len(next(iter(given[0][1].values()), ()))
        for key, value in kwargs.items():
            if isinstance(value, (list, tuple)) and len(value) == length and all(isinstance(v, (int, float)) for v in value):
                raise UsageError("%s: expected a numpy float array (numpy.asarray(x, dtype=float))" % key)
    elif logs is not None and not paths:
        raise UsageError("logs: no log given")
    args = list(words)
    options = []
    for key, value in (col or {}).items():
        options += ["--col", "%s=%s" % (key, value)]
    for key, value in kwargs.items():
        options += _flag_words(key, value)
    with _Scratch() as scratch, _Params(params) as params_path:
        if params_path is not None and kind == "validation":  # validate PARAMS LOGS...
            paths = [params_path] + paths
        elif params_path is not None:
            options += ["--params", params_path]
        shown = ["driveid." + function] + paths + options
        command_line = " ".join(shlex.quote(w) for w in shown)
        extra = []
        output = None
        if kind == "fit":
            extra = ["-q"]
            if trace is True:  # the trace in memory only: computed, written where it is dropped
                extra += ["--trace", scratch.path("trace.csv")]
        elif kind in ("gains", "design", "simulate", "result-o") and "output" not in kwargs and "o" not in kwargs:
            output = scratch.path("output")
            extra = ["-o", output]
        elif kind == "validation" and "json" not in kwargs:
            extra = ["--json"]
        raw = _driveid.run(tool, args + options + extra + ["--"] + paths, command_line, given, progress)
        if "error" in raw:
            _raise(raw["error"])
        text = raw["out"].decode("utf-8", "replace")
        if kind == "fit":
            fits = [Fit(f) for f in raw["fits"]]
            if not fits:
                raise Error("%s: the command computed no fit" % function)
            return fits[-1] if len(fits) == 1 else fits
        written = None
        if output is not None and os.path.exists(output):
            with open(output, encoding="utf-8") as f:
                written = f.read()
    data_out = None
    warnings = []
    if text.lstrip().startswith("{"):
        data_out = json.loads(text)
    elif written is not None and kind == "gains":
        import yaml  # Debian's python3-yaml, imported where used

        data_out = yaml.safe_load(written)
    if isinstance(data_out, dict):
        warnings = list(data_out.get("warnings", []) or [])
    cls = {"gains": Gains, "design": Design, "validation": Validation}.get(kind, Result)
    return cls(function, text, data_out, written, warnings)


def _command(function, tool, words, kind, doc):
    def call(logs=None, *, progress=None, **kwargs):
        return _run_command(function, tool, words, kind, logs, kwargs, progress)

    call.__name__ = function
    call.__qualname__ = function
    call.__doc__ = doc + """

    logs: log path(s), read by the command's readers; or float numpy arrays named as the log's
    columns (t=, q=, tau=, ...); or data= (a DataFrame or mapping of columns) with col= (logical
    name -> its column or a --col expression). params: a parameter file path or a dict. Every other
    keyword is the flag of the same name (torque_timing= is --torque-timing; True for a flag; a
    list repeats it). trace=True (fits): Fit.trace holds the --trace columns; a path writes them
    there as well. progress: a callable taking each line the command writes on stderr
    (warnings, progress), else they go to stderr. docs/python.md.
    """
    return call


_FIT = "fit"
axis = _command("axis", "drivetrain-fit", ["axis"], _FIT, "``drivetrain-fit axis``: inertia, friction, offset (and gravity) of a rigid axis (docs/models.md#axis): arrays t, q, tau (or i with axis.k_t in params), optional qd. Returns a Fit.")
joint = _command("joint", "drivetrain-fit", ["joint"], _FIT, "``drivetrain-fit joint``: an elastic joint's parameters (docs/models.md#joint). Returns a Fit.")
step = _command("step", "drivetrain-fit", ["step"], _FIT, "``drivetrain-fit step``: the drive train from step responses (docs/models.md). Returns a Fit.")
frf = _command("frf", "drivetrain-fit", ["frf"], _FIT, "``drivetrain-fit frf``: the elastic joint from a measured frequency response. Returns a Fit.")
robot = _command("robot", "drivetrain-fit", ["robot"], _FIT, "``drivetrain-fit robot``: the planar robot's or, with urdf=, a serial arm's rigid-body model. Returns a Fit.")
cdrive_friction = _command("cdrive_friction", "cdrive-fit", ["friction"], _FIT, "``cdrive-fit friction``: the C-drive's dissipation beta, gamma, delta, eta. Returns a Fit.")
cdrive_inertia = _command("cdrive_inertia", "cdrive-fit", ["inertia"], _FIT, "``cdrive-fit inertia``: the C-drive's inertia matrix. Returns a Fit.")
validate = _command("validate", "drivetrain-fit", ["validate"], "validation", "``drivetrain-fit validate``: a parameter file's prediction of held-out logs. Returns a Validation.")
cdrive_validate = _command("cdrive_validate", "cdrive-fit", ["validate"], "validation", "``cdrive-fit validate``: the C-drive parameters' prediction of held-out logs. Returns a Validation.")
gains = _command("gains", "drivetrain-fit", ["gains"], "gains", "``drivetrain-fit gains``: feedback gains from a parameter file (docs/models.md#feedback-gains). Returns Gains.")
design_axis = _command("design_axis", "drivetrain-fit", ["design", "axis"], "design", "``drivetrain-fit design axis``: the next experiment for an axis. Returns a Design.")
design_joint = _command("design_joint", "drivetrain-fit", ["design", "joint"], "design", "``drivetrain-fit design joint``: the next experiment for an elastic joint. Returns a Design.")
design_robot = _command("design_robot", "drivetrain-fit", ["design", "robot"], "design", "``drivetrain-fit design robot``: the next experiment for a serial arm. Returns a Design.")
compare = _command("compare", "drivetrain-fit", ["compare"], "result", "``drivetrain-fit compare``: drift between two parameter files (GateFailed on drift). Returns a Result.")
report = _command("report", "drivetrain-fit", ["report"], "result", "``drivetrain-fit report``: the derived quantities of a parameter file. Returns a Result.")
export = _command("export", "drivetrain-fit", ["export"], "result-o", "``drivetrain-fit export``: MJCF, URDF or WPILib constants from a parameter file. Returns a Result.")
simulate_axis = _command("simulate_axis", "drivetrain-fit", ["simulate", "axis"], "simulate", "``drivetrain-fit simulate axis``: a synthetic axis log. Returns a Result with .log.")
simulate_step = _command("simulate_step", "drivetrain-fit", ["simulate", "step"], "simulate", "``drivetrain-fit simulate step``: synthetic step logs. Returns a Result with .log.")
simulate_joint = _command("simulate_joint", "drivetrain-fit", ["simulate", "joint"], "simulate", "``drivetrain-fit simulate joint``: a synthetic elastic-joint log. Returns a Result with .log.")
simulate_robot = _command("simulate_robot", "drivetrain-fit", ["simulate", "robot"], "simulate", "``drivetrain-fit simulate robot``: a synthetic robot log. Returns a Result with .log.")
cdrive_simulate = _command("cdrive_simulate", "cdrive-fit", ["simulate"], "simulate", "``cdrive-fit simulate``: a closed-loop C-drive simulation. Returns a Result with .log.")
