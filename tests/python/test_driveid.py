"""The Python module driveid (docs/python.md) against the command line.

Run by ctest (python_test) with PYTHONPATH at the build's python/ and
DRIVEID_BIN at its apps/: every number equal to the command's to the last
bit, on a path and on arrays; the parameter file as -o writes it; each
exception class with the command's text; arrays of the wrong length, NaN
or dtype refused by name; a thread pool's fits equal to serial ones.
"""

import concurrent.futures
import json
import os
import subprocess

import numpy
import pytest

import driveid

BIN = os.environ.get("DRIVEID_BIN", "build/default/apps")
SRC = os.environ.get("DRIVEID_SRC", ".")


def run(*args, check=True):
    return subprocess.run([os.path.join(BIN, "drivetrain-fit"), *args], capture_output=True, text=True, check=check)


@pytest.fixture(scope="module")
def log(tmp_path_factory):
    """A simulated axis log (the tool's own simulator: quantised encoder, noisy torque)."""
    path = tmp_path_factory.mktemp("axis") / "axis.csv"
    run("simulate", "axis", "--params", os.path.join(SRC, "data/axis_example.yaml"), "--noise", "0.05", "-o", str(path))
    return path


def cli_fit(*args):
    out = run("axis", *args, "--json", "-q")
    return json.loads(out.stdout)


def columns(path):
    lines = [line for line in open(path, encoding="utf-8") if not line.startswith("#")]
    header = lines[0].strip().split(",")
    table = numpy.loadtxt(lines[1:], delimiter=",", ndmin=2)
    return {name: numpy.ascontiguousarray(table[:, k]) for k, name in enumerate(header)}


def test_path_equals_the_command_line_to_the_last_bit(log):
    expected = cli_fit(str(log))
    fit = driveid.axis(str(log))
    assert fit.names == list(expected["estimates"])
    for name, e in expected["estimates"].items():
        assert fit.estimates[name].value == e["value"]
        assert fit.estimates[name].std == e["std"]
    assert fit.warnings == expected["warnings"]
    assert fit.covariance.shape == (len(fit.names), len(fit.names))
    assert numpy.allclose(numpy.diag(fit.covariance), [fit.estimates[n].std ** 2 for n in fit.names], rtol=1e-12)
    assert "inertia" in repr(fit)


def test_arrays_and_a_dataframe_like_mapping_equal_the_file(log):
    expected = cli_fit(str(log))
    c = columns(log)
    arrays = {k: c[k] for k in ("t", "q", "tau", "qd") if k in c}
    fit = driveid.axis(**arrays)
    for name, e in expected["estimates"].items():
        assert fit.estimates[name].value == e["value"]
        assert fit.estimates[name].std == e["std"]
    renamed = {"time": c["t"], "position": c["q"], "torque": c["tau"]}
    col = {"t": "time", "q": "position", "tau": "torque"}
    if "qd" in c:
        renamed["rate"] = c["qd"]
        col["qd"] = "rate"
    by_mapping = driveid.axis(data=renamed, col=col)
    assert by_mapping.to_dict()["estimates"] == fit.to_dict()["estimates"]


def test_the_parameter_file_is_the_commands(log, tmp_path):
    run("axis", str(log), "-o", str(tmp_path / "cli.yaml"), "-q")
    fit = driveid.axis(str(log))
    fit.to_yaml(tmp_path / "py.yaml")

    def body(path):
        return [line for line in path.read_text().splitlines() if "command:" not in line]

    assert body(tmp_path / "py.yaml") == body(tmp_path / "cli.yaml")
    (tmp_path / "dir").mkdir()
    with pytest.raises(driveid.InputError, match="not a regular file"):
        fit.to_yaml(tmp_path / "dir")


def test_trace_has_the_commands_columns(log):
    trace = driveid.axis(str(log), trace=True).trace
    assert trace is not None and len(trace["t"]) > 100
    assert driveid.axis(str(log)).trace is None  # computed when asked for (trace=True or a path)


def test_usage_errors_carry_the_commands_text(log):
    with pytest.raises(driveid.UsageError, match="method") as e:
        driveid.axis(str(log), method="bogus")
    assert e.value.exit_code == 2
    with pytest.raises(driveid.UsageError, match="decimation"):
        driveid.axis(str(log), decimation=-1)
    with pytest.raises(driveid.UsageError, match="free"):
        driveid.axis(str(log), free="inertia,nonsense")
    cli = run("axis", str(log), "--free", "inertia,nonsense", check=False)
    assert cli.returncode == 2
    with pytest.raises(driveid.UsageError) as e:
        driveid.axis(str(log), free="inertia,nonsense")
    assert str(e.value) in cli.stderr


def test_input_errors_name_the_file_or_the_array(log, tmp_path):
    with pytest.raises(driveid.InputError, match="missing.csv") as e:
        driveid.axis(str(tmp_path / "missing.csv"))
    assert e.value.exit_code == 3
    c = columns(log)
    t, q, tau = c["t"], c["q"], c["tau"]
    with pytest.raises(driveid.InputError, match="q: .* values, t has"):
        driveid.axis(t=t, q=q[:-1], tau=tau)
    bad = tau.copy()
    bad[7] = numpy.nan
    with pytest.raises(driveid.InputError, match=r"tau\[7\]: not a finite number"):
        driveid.axis(t=t, q=q, tau=bad)
    with pytest.raises(driveid.UsageError, match="q: expected floats"):
        driveid.axis(t=t, q=numpy.arange(len(t)), tau=tau)
    with pytest.raises(driveid.UsageError, match="tau: expected a numpy float array"):
        driveid.axis(t=t, q=q, tau=list(tau))
    with pytest.raises(driveid.InputError, match="arrays: missing column 'tau' or 'i'"):
        driveid.axis(t=t, q=q)
    with pytest.raises(driveid.InputError, match="time not strictly increasing"):
        driveid.axis(t=t[::-1].copy(), q=q, tau=tau)


def test_identification_error_names_the_parameters():
    # Constant speed: the acceleration is zero, the inertia undetermined.
    t = numpy.arange(0.0, 5.0, 0.001)
    q = 2.0 * t
    tau = 0.3 * numpy.ones_like(t) + 0.01 * numpy.sin(37.0 * t)
    with pytest.raises(driveid.IdentificationError) as e:
        driveid.axis(t=t, q=q, tau=tau, method="idim", free="inertia,viscous",
                     params={"axis": {"coulomb": 0.0, "offset": 0.0}})
    assert e.value.exit_code == 4
    assert "inertia" in e.value.parameters
    assert "inertia" in str(e.value)


def test_params_as_a_dict_and_as_a_path(log):
    by_path = driveid.axis(str(log), params=os.path.join(SRC, "data/axis_example.yaml"))
    as_dict = {"axis": {"inertia": 0.05, "viscous": 0.2, "coulomb": 1.0, "offset": 0.3, "n_g": 80}}
    by_dict = driveid.axis(str(log), params=as_dict)
    assert by_dict.to_dict()["estimates"] == by_path.to_dict()["estimates"]
    expected = cli_fit(str(log), "--params", os.path.join(SRC, "data/axis_example.yaml"))
    for name, e in expected["estimates"].items():
        assert by_path.estimates[name].value == e["value"]


def test_a_thread_pool_matches_serial_fits(log):
    c = columns(log)
    cases = [dict(t=c["t"], q=c["q"], tau=c["tau"] * (1.0 + 0.01 * k)) for k in range(4)]
    serial = [driveid.axis(**case).to_dict()["estimates"] for case in cases]
    with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
        parallel = list(pool.map(lambda case: driveid.axis(**case).to_dict()["estimates"], cases))
    assert parallel == serial
