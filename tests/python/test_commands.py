"""Every command of the Python module (docs/python.md) against the tool.

Each function runs on the shipped data (data/) and on logs made here, and
its numbers equal `drivetrain-fit ... --json` / `cdrive-fit ... --json` to
the last bit (estimates, std, warnings); printed outputs equal the
command's standard output byte for byte. Exceptions mirror exit codes with
the command's message; a thread pool's fits equal serial ones; the
progress callback receives the command's stderr lines.
"""

import concurrent.futures
import json
import math
import os
import subprocess

import numpy
import pytest

import driveid

BIN = os.environ.get("DRIVEID_BIN", "build/default/apps")
SRC = os.environ.get("DRIVEID_SRC", ".")


def data(name):
    return os.path.join(SRC, "data", name)


def tool(name, *args, check=True):
    return subprocess.run([os.path.join(BIN, name), *args], capture_output=True, text=True, check=check)


def assert_same_fit(fit, *command):
    expected = json.loads(tool(*command, "--json", "-q").stdout)
    if "estimates" not in expected:  # frf: the fit inside its own summary
        expected = expected["fit"]
    assert fit.names == list(expected["estimates"])
    for name, e in expected["estimates"].items():
        assert fit.estimates[name].value == e["value"], name
        assert fit.estimates[name].std == e["std"], name
    assert fit.warnings == expected["warnings"]


def test_joint_step_robot_and_the_cdrive_fits_equal_the_tools():
    assert_same_fit(driveid.joint(data("joint_example.csv"), params=data("joint_start.yaml")),
                    "drivetrain-fit", "joint", data("joint_example.csv"), "--params", data("joint_start.yaml"))
    free = "d_g,Theta_motor,tau_c,offset"
    fit = driveid.step(data("fig6_step.csv"), params=data("paper000_start.yaml"), model="full", free=free, trace=True)
    assert_same_fit(fit, "drivetrain-fit", "step", data("fig6_step.csv"), "--params", data("paper000_start.yaml"),
                    "--model", "full", "--free", free)
    assert fit.trace is not None and len(fit.trace) >= 3
    assert_same_fit(driveid.robot(data("robot_triangle.csv"), params=data("robot_start.yaml")),
                    "drivetrain-fit", "robot", data("robot_triangle.csv"), "--params", data("robot_start.yaml"))
    slow = [data("cdrive_slow_%s.csv" % p) for p in ("translation", "rotation", "helical")]
    fit = driveid.cdrive_friction(slow, params=data("cdrive_start.yaml"))
    assert_same_fit(fit, "cdrive-fit", "friction", *slow, "--params", data("cdrive_start.yaml"))
    assert "beta" in " ".join(fit.names)


def two_mass_log(path):
    """A two-mass joint under a multisine (J_m 0.5, J_l 1.5, k 2000, gear 10), written independently of the tool."""
    n, jm, jl, k, d, bm, rate, period, ns = 10, 0.5, 1.5, 2000.0, 2.0, 6.0, 1000, 2000, 20
    h = 1.0 / (rate * ns)
    rng = numpy.random.default_rng(7)
    lines = numpy.arange(1, 61)
    xm = vm = xl = vl = 0.0
    rows = []
    for i in range(8 * period):
        p = i % period
        u = float(numpy.sum(0.05 * numpy.cos(2 * math.pi * lines * p / period - math.pi * lines * (lines - 1) / 60)))
        rows.append((i / rate, u, n * xm, n * vm + 0.02 * (rng.random() - 0.5), xl))
        for _ in range(ns):
            f = k * (xm - xl) + d * (vm - vl)
            vm += h * (n * u - f - bm * vm) / jm
            vl += h * f / jl
            xm += h * vm
            xl += h * vl
    numpy.savetxt(path, numpy.array(rows), delimiter=",", header="t,tau,q_motor,qd_motor,q_link", comments="",
                  fmt="%.9g")


def test_frf_equals_the_tool(tmp_path):
    log = tmp_path / "twomass.csv"
    two_mass_log(log)
    (tmp_path / "gear.yaml").write_text("joint:\n  gear_ratio: 10\n")
    gear = str(tmp_path / "gear.yaml")
    fit = driveid.frf(str(log), params=gear, fit="two-mass")
    assert_same_fit(fit, "drivetrain-fit", "frf", str(log), "--params", gear, "--fit", "two-mass")
    assert "stiffness" in fit.names


def test_arrays_and_a_dataframe_equal_the_file(tmp_path):
    path = data("joint_example.csv")
    lines = [line for line in open(path, encoding="utf-8") if not line.startswith("#")]
    header = lines[0].strip().split(",")
    table = numpy.loadtxt(lines[1:], delimiter=",", ndmin=2)
    columns = {name: numpy.ascontiguousarray(table[:, k]) for k, name in enumerate(header)}
    by_file = driveid.joint(path, params=data("joint_start.yaml"))
    by_arrays = driveid.joint(params=data("joint_start.yaml"), **columns)
    assert by_arrays.to_dict()["estimates"] == by_file.to_dict()["estimates"]
    renamed = {"c%d" % k: v for k, v in enumerate(columns.values())}
    col = {name: "c%d" % k for k, name in enumerate(columns)}
    by_frame = driveid.joint(data=renamed, col=col, params=data("joint_start.yaml"))
    assert by_frame.to_dict()["estimates"] == by_file.to_dict()["estimates"]
    # --from/--to crop arrays as they crop the file.
    cropped = driveid.joint(params=data("joint_start.yaml"), to=5.0, **columns)
    assert_same_fit(cropped, "drivetrain-fit", "joint", path, "--params", data("joint_start.yaml"), "--to", "5")
    # Refused by name: wrong length, NaN, integer dtype.
    bad = dict(columns, t=columns["t"][:-1])
    with pytest.raises(driveid.InputError, match="values, t has"):
        driveid.joint(params=data("joint_start.yaml"), **bad)
    nan = dict(columns)
    nan[header[1]] = columns[header[1]].copy()
    nan[header[1]][3] = float("nan")
    with pytest.raises(driveid.InputError, match=r"%s\[3\]" % header[1]):
        driveid.joint(params=data("joint_start.yaml"), **nan)
    with pytest.raises(driveid.UsageError, match="dtype"):
        driveid.joint(params=data("joint_start.yaml"), **dict(columns, t=numpy.arange(len(columns["t"]))))


def rows(text):
    return [line for line in text.splitlines() if not line.startswith("#")]


def test_printed_outputs_equal_the_tools(tmp_path):
    gains = driveid.gains(data("axis_example.yaml"))
    out = tmp_path / "gains.yaml"
    cli = tool("drivetrain-fit", "gains", data("axis_example.yaml"), "-o", str(out))
    assert repr(gains) == cli.stdout
    assert gains.parameter_file == out.read_text()
    assert gains.data["feedback"]["kp"]["value"] > 0
    report = driveid.report(data("paper000.yaml"))
    assert repr(report) == tool("drivetrain-fit", "report", data("paper000.yaml")).stdout
    simulated = driveid.simulate_axis(params=data("axis_example.yaml"), noise=0.05, duration=3, seed=2)
    cli_log = tmp_path / "sim.csv"
    tool("drivetrain-fit", "simulate", "axis", "--params", data("axis_example.yaml"), "--noise", "0.05",
         "--duration", "3", "--seed", "2", "-o", str(cli_log))
    assert rows(simulated.parameter_file) == rows(cli_log.read_text())  # the comments name the command line
    assert len(simulated.log["t"]) == len(simulated.log["tau"]) > 100
    cycle = driveid.cdrive_simulate(program="translation", params=data("cdrive_table1.yaml"), cycles=1)
    assert set(cycle.log) >= {"t"}
    fit = driveid.axis(t=simulated.log["t"], q=simulated.log["q"], tau=simulated.log["tau"],
                       params=data("axis_example.yaml"))
    fit.to_yaml(tmp_path / "axis_fit.yaml")
    prior = str(tmp_path / "axis_fit.yaml")
    limits = {"duration": 5, "max_position": 1, "max_speed": 2, "max_torque": 3}
    design = driveid.design_axis(params=prior, **limits)
    reference = tmp_path / "ref.csv"
    assert repr(design) == tool("drivetrain-fit", "design", "axis", "--params", prior, "--duration", "5",
                                "--max-position", "1", "--max-speed", "2", "--max-torque", "3",
                                "-o", str(reference)).stdout
    assert rows(design.parameter_file) == rows(reference.read_text())
    exported = driveid.export(prior, to="c-header")
    header = tool("drivetrain-fit", "export", prior, "--to", "c-header").stdout
    assert exported.parameter_file.replace("driveid.export", "drivetrain-fit export") == header
    compared = driveid.compare([prior, prior], json=True)
    assert compared.data == json.loads(tool("drivetrain-fit", "compare", prior, prior, "--json").stdout)
    # A drift past the gate: GateFailed (exit 1), after the report.
    driveid.axis(str(cli_log), params=data("axis_example.yaml"), to=1.5).to_yaml(tmp_path / "short.yaml")
    with pytest.raises(driveid.GateFailed):
        driveid.compare([prior, str(tmp_path / "short.yaml")], fail_above=0.0001)
    assert tool("drivetrain-fit", "compare", prior, str(tmp_path / "short.yaml"), "--fail-above", "0.0001",
                check=False).returncode == 1
    assert set(design.log) >= {"t", "q"}
    validation = driveid.validate(str(cli_log), params=prior)
    expected = json.loads(tool("drivetrain-fit", "validate", prior, str(cli_log), "--json").stdout)
    assert dict(validation.data, command="") == dict(expected, command="")  # all but the command line
    assert "fit %" in repr(validation) and str(cli_log) in repr(validation)


def test_exceptions_mirror_the_exit_codes(tmp_path):
    with pytest.raises(driveid.UsageError) as usage:
        driveid.gains(data("axis_example.yaml"), no_such_flag=1)
    cli = tool("drivetrain-fit", "gains", "--no-such-flag", "1", "--", data("axis_example.yaml"), check=False)
    assert cli.returncode == 2 and str(usage.value) in cli.stderr
    with pytest.raises(driveid.InputError) as missing:
        driveid.joint(str(tmp_path / "missing.csv"), params=data("joint_start.yaml"))
    cli = tool("drivetrain-fit", "joint", str(tmp_path / "missing.csv"), "--params", data("joint_start.yaml"),
               check=False)
    assert cli.returncode == 3 and str(missing.value) in cli.stderr


def test_a_thread_pool_equals_serial_runs_and_progress_reaches_the_callback():
    def one(k):
        return driveid.joint(data("joint_example.csv"), params=data("joint_start.yaml"), to=4.0 + k).to_dict()

    serial = [one(k) for k in range(4)]
    with concurrent.futures.ThreadPoolExecutor(4) as pool:
        parallel = list(pool.map(one, range(4)))
    assert [p["estimates"] for p in parallel] == [s["estimates"] for s in serial]
    lines = []
    driveid.joint(data("joint_example.csv"), params=data("joint_start.yaml"), verbose=True, progress=lines.append)
    assert any(line.startswith("iteration") for line in lines)
