"""driveid from Python: the command line's fits as functions (docs/python.md).

Each function takes keyword arguments named as the command's flags
(``--torque-timing`` is ``torque_timing=``) and computes exactly what the
command computes (the same C++ function), so the numbers are the command
line's to the last bit. Inputs are log paths (read by the same readers:
CSV, MAT, SysId JSON, .wpilog, ROS bags, MCAP), numpy float arrays
(``t=``, ``q=``, ``tau=``, ...), or a DataFrame or dict of columns
(``data=df, col={"t": "time", ...}``). Refusals raise exceptions that
mirror the command's exit codes.

This round the module offers ``axis``; the other commands are not in it
yet (docs/python.md lists what is).
"""

import json
import os
import shlex
import tempfile

from . import _driveid

__version__ = _driveid.version
__all__ = ["axis", "Fit", "Estimate", "Error", "UsageError", "InputError", "IdentificationError", "GateFailed"]


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
            import numpy

            lines = [line for line in text.splitlines() if line and not line.startswith("#")]
            header = lines[0].split(",")
            rows = [line.split(",") for line in lines[1:]]
            trace = {}
            for k, name in enumerate(header):
                column = [row[k] for row in rows]
                try:
                    trace[name] = numpy.array(column, dtype=float)
                except ValueError:
                    trace[name] = numpy.array(column)
            self._trace = trace
        return self._trace

    def to_yaml(self, path):
        """Writes the parameter file atomically (a regular file or a new one; never renamed over anything else)."""
        path = os.fspath(path)
        if os.path.lexists(path) and not os.path.isfile(path):
            raise InputError("%s: not a regular file: the parameter file is not written over it" % path)
        directory = os.path.dirname(os.path.abspath(path))
        fd, temporary = tempfile.mkstemp(prefix=".driveid-", dir=directory)
        try:
            with os.fdopen(fd, "w", encoding="utf-8") as f:
                f.write(self.parameter_file)
            os.replace(temporary, path)
        except BaseException:
            os.unlink(temporary)
            raise

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


def _names(value):
    if value is None:
        return None
    if isinstance(value, str):
        return [v for v in value.split(",")]
    return [str(v) for v in value]


def _paths(value):
    if value is None:
        return []
    if isinstance(value, (str, os.PathLike)):
        return [os.fspath(value)]
    return [os.fspath(v) for v in value]


def _columns(data, col, names):
    """The arrays named `names` from a DataFrame or mapping, through `col` (logical name -> its column)."""
    col = dict(col or {})
    out = {}
    for name in names:
        key = col.get(name, name)
        try:
            column = data[key]
        except (KeyError, IndexError):
            if name in col:
                raise InputError("data: no column %r (col[%r])" % (key, name)) from None
            continue
        out[name] = column.to_numpy() if hasattr(column, "to_numpy") else column
    return out


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


def _command_line(command, logs, options):
    words = ["driveid." + command] + list(logs)
    for key, value in options.items():
        if value is None or key in ("logs",):
            continue
        flag = "--" + key.replace("_", "-")
        if isinstance(value, bool):
            if value:
                words.append(flag)
        elif isinstance(value, list):
            for v in value:
                words += [flag, str(v)]
        else:
            words += [flag, str(value)]
    return " ".join(shlex.quote(w) for w in words)


_AXIS_ARRAYS = ("t", "q", "qd", "tau", "i", "tau_known")


def axis(logs=None, *, t=None, q=None, tau=None, i=None, qd=None, tau_known=None, data=None, col=None, name="arrays",
         params=None, free=None, method=None, linear=None, cutoff=None, decimation=None, torque_timing=None,
         validate=None, trace=True):
    """``drivetrain-fit axis``: inertia, friction, offset (and gravity) of a rigid axis (docs/models.md#axis).

    logs: path(s) of axis logs; or arrays t, q, tau (or i with axis.k_t in params), optional qd and
    tau_known; or data (a DataFrame or dict of columns) with col mapping the logical names to its
    columns. col with paths: {"q": "pi/180*#2", ...} as --col. name: the arrays' log name in messages.
    params: a parameter file path or a dict with an ``axis`` section. free, method, linear, cutoff,
    decimation, torque_timing, validate: as the flags. Returns a Fit.
    """
    paths = _paths(logs)
    arrays = None
    given = {"t": t, "q": q, "tau": tau, "i": i, "qd": qd, "tau_known": tau_known}
    if data is not None:
        if paths or any(v is not None for v in given.values()):
            raise UsageError("data: give data=, arrays or log paths, not several")
        arrays = _columns(data, col, _AXIS_ARRAYS)
        col = None
    elif any(v is not None for v in given.values()):
        if paths:
            raise UsageError("logs: give log paths or arrays, not both")
        arrays = {k: v for k, v in given.items() if v is not None}
    options = {"logs": paths, "free": _names(free), "method": method, "linear": linear, "cutoff": cutoff,
               "decimation": decimation, "torque_timing": torque_timing, "validate": _paths(validate) or None,
               "col": ["%s=%s" % (k, v) for k, v in (col or {}).items()] or None}
    options = {k: v for k, v in options.items() if v is not None}
    with _Params(params) as params_path:
        if params_path is not None:
            options["params"] = params_path
        command_line = _command_line("axis", paths, {k: v for k, v in options.items() if k != "logs"})
        options["trace"] = bool(trace)
        raw = _driveid.axis(options, arrays, name, command_line)
    if "error" in raw:
        _raise(raw["error"])
    return Fit(raw)
