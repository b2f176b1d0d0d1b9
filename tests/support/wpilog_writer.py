#!/usr/bin/env python3
"""An independent WPILib DataLog writer for the tests (written from the
published format, not from driveid's reader): a SysIdRoutine of a simulated
motor as a robot writes it.

The motor: Ka dv/dt = V - Ks sgn(v) - Kv v (v in m/s, V in volts),
integrated at 1 kHz; logged every 20 ms with jitter, voltage with noise,
position quantised (an encoder), velocity with noise; the three entries at
their own times (a few microseconds apart, as SysIdRoutineLog writes them),
then the test state. The first quasistatic-forward run is aborted and rerun.
Beside the routine: a second motor ('follower'), a struct entry, an
NT-mirrored entry with negative (retained) timestamps, a Finish and a
Set-metadata control record.

usage: wpilog_writer.py OUT.wpilog [--same-times CSV_PREFIX] [--seed N] [--short]
                        [--names sysid|robotpy|advantagekit] [--no-state] [--ks VOLTS]
                        [--latency MIN_MS MAX_MS] [--mechanism flywheel|elevator|arm]
                        [--rotations] [--kg VOLTS] [--dynamic SECONDS]
  --same-times: the three entries share each loop's timestamp, and each
  test's samples are written to CSV_PREFIX<test>.csv (t, voltage, position,
  velocity) exactly as logged, for a round trip; --short: tests of 0.2 s
  (a small file, e.g. a fuzzing seed); --names: the entries' names as
  SysIdRoutine writes them (default), as a RobotPy robot's own logging
  (/drive/appliedVoltage, /drive/leftPosition, /drive/leftVelocity,
  /sysid/testType with SysId's state names; no units) or as AdvantageKit
  (/RealOutputs/Shooter/SysIdState holding the enum's names
  kQuasistaticForward ..., /Shooter/LeaderAppliedVolts,
  /Shooter/LeaderPositionRad, /Shooter/LeaderVelocityRadPerSec; the
  follower's volts and current only); --no-state: no state entry; --ks:
  the motor's static friction (default 0.25 V); --latency: the position
  and velocity logged are as old as a CAN status frame, uniformly
  MIN_MS..MAX_MS at each loop (default: current); --mechanism: an
  elevator adds a constant gravity Kg (V), an arm Kg cos(q) with q in
  radians from the horizontal (starting at -1 rad), both Kg from --kg
  (default 0.6 V); --rotations: the arm's position and velocity logged in
  rotations, as SysIdRoutine logs an angular mechanism (units "Rotation",
  "Rotation per Second"; the model's Kv and Ka stay per radian);
  --dynamic: the dynamic tests' length (default 2.5 s; 0.4 s are 20
  samples at 50 Hz).
"""
import math
import random
import struct
import sys

KS, KV, KA = 0.25, 2.5, 0.3


def varint(value, size):
    return value.to_bytes(size, "little", signed=False)


def length_of(value, limit):
    for n in range(1, limit + 1):
        if value < 1 << (8 * n):
            return n
    raise ValueError(value)


def record(entry, timestamp_us, payload):
    """One record with the shortest fields (exercises the length byte)."""
    raw_time = timestamp_us & ((1 << 64) - 1)
    e, s = length_of(entry, 4), length_of(len(payload), 4)
    t = 8 if timestamp_us < 0 else length_of(raw_time, 8)
    head = (e - 1) | ((s - 1) << 2) | ((t - 1) << 4)
    return bytes([head]) + varint(entry, e) + varint(len(payload), s) + varint(raw_time, t) + payload


def text(s):
    b = s.encode()
    return struct.pack("<I", len(b)) + b


def start(entry, name, type_, metadata, timestamp_us=0):
    return record(0, timestamp_us, bytes([0]) + struct.pack("<I", entry) + text(name) + text(type_) + text(metadata))


def finish(entry, timestamp_us):
    return record(0, timestamp_us, bytes([1]) + struct.pack("<I", entry))


def set_metadata(entry, metadata, timestamp_us):
    return record(0, timestamp_us, bytes([2]) + struct.pack("<I", entry) + text(metadata))


def main():
    out = sys.argv[1]
    same_times = "--same-times" in sys.argv
    prefix = sys.argv[sys.argv.index("--same-times") + 1] if same_times else None
    seed = int(sys.argv[sys.argv.index("--seed") + 1]) if "--seed" in sys.argv else 1
    ks = float(sys.argv[sys.argv.index("--ks") + 1]) if "--ks" in sys.argv else KS
    latency = (tuple(float(x) * 1e-3 for x in sys.argv[sys.argv.index("--latency") + 1:sys.argv.index("--latency") + 3])
               if "--latency" in sys.argv else (0.0, 0.0))
    history = []  # (t, q, v) at 1 kHz, for a state as old as a status frame
    rng = random.Random(seed)
    log = bytearray(b"WPILOG" + struct.pack("<H", 0x0100) + text("driveid test writer"))
    mech = "Shooter"
    names = sys.argv[sys.argv.index("--names") + 1] if "--names" in sys.argv else "sysid"
    mechanism = sys.argv[sys.argv.index("--mechanism") + 1] if "--mechanism" in sys.argv else "flywheel"
    assert mechanism in ("flywheel", "elevator", "arm"), mechanism
    kg = float(sys.argv[sys.argv.index("--kg") + 1]) if "--kg" in sys.argv else 0.6
    rotations = "--rotations" in sys.argv
    assert not rotations or mechanism == "arm", "--rotations is for an arm"
    scale = 1.0 / (2.0 * math.pi) if rotations else 1.0  # logged units per model unit
    dynamic = float(sys.argv[sys.argv.index("--dynamic") + 1]) if "--dynamic" in sys.argv else 2.5
    position_unit, velocity_unit = (("Rotation", "Rotation per Second") if rotations else
                                    ("Radian", "Radian per Second") if mechanism == "arm" else
                                    ("Meter", "Meter per Second"))
    # The name each role is written under (role names as SysIdRoutine's).
    rename = {
        "sysid": {},
        "robotpy": {"voltage-leader-" + mech: "/drive/appliedVoltage", "position-leader-" + mech: "/drive/leftPosition",
                    "velocity-leader-" + mech: "/drive/leftVelocity", "voltage-follower-" + mech: "/drive/rightVoltage",
                    "position-follower-" + mech: "/drive/rightPosition",
                    "velocity-follower-" + mech: "/drive/rightVelocity", "sysid-test-state-" + mech: "/sysid/testType"},
        "advantagekit": {"voltage-leader-" + mech: "/Shooter/LeaderAppliedVolts",
                         "position-leader-" + mech: "/Shooter/LeaderPositionRad",
                         "velocity-leader-" + mech: "/Shooter/LeaderVelocityRadPerSec",
                         "voltage-follower-" + mech: "/Shooter/FollowerAppliedVolts",
                         "position-follower-" + mech: "/Shooter/FollowerCurrentAmps",
                         "velocity-follower-" + mech: "/Shooter/FollowerTempCelsius",
                         "sysid-test-state-" + mech: "/RealOutputs/Shooter/SysIdState"},
    }[names]
    kotlin_state = {"quasistatic-forward": "kQuasistaticForward", "quasistatic-reverse": "kQuasistaticReverse",
                    "dynamic-forward": "kDynamicForward", "dynamic-reverse": "kDynamicReverse", "none": "kNone"}
    state_text = (lambda s: kotlin_state[s]) if names == "advantagekit" else (lambda s: s)
    no_state = "--no-state" in sys.argv
    ids = {}
    for i, (name, type_, meta) in enumerate([
            ("voltage-leader-" + mech, "double", "Volt"),
            ("position-leader-" + mech, "double", position_unit),
            ("velocity-leader-" + mech, "double", velocity_unit),
            ("voltage-follower-" + mech, "double", "Volt"),
            ("position-follower-" + mech, "double", "Meter"),
            ("velocity-follower-" + mech, "double", "Meter per Second"),
            ("sysid-test-state-" + mech, "string", ""),
            ("struct:Pose2d", "struct:Pose2d", ""),
            ("NT:/SmartDashboard/retained", "double", '{"source":"NT"}'),
            ("console", "string", "")]):
        ids[name] = 300 + i  # two-byte entry ids
        if no_state and name.startswith("sysid-test-state-"):
            continue
        log += start(ids[name], rename.get(name, name), type_, meta if names == "sysid" else "", 1000)
    # Retained NetworkTables values: negative timestamps.
    log += record(ids["NT:/SmartDashboard/retained"], -5, struct.pack("<d", 42.0))
    log += record(ids["NT:/SmartDashboard/retained"], -1, struct.pack("<d", 43.0))
    log += set_metadata(ids["console"], "changed", 2000)

    tests = [("quasistatic-forward", 1.5), ("quasistatic-forward", 5.0), ("quasistatic-reverse", 5.0),
             ("dynamic-forward", dynamic), ("dynamic-reverse", dynamic)]
    if "--short" in sys.argv:
        tests = [(name, 0.2) for name, _ in tests]
    t = 2.0  # s
    v = 0.0
    q = -1.0 if mechanism == "arm" else 0.0
    csv = {}
    for test, length in tests:
        direction = 1.0 if test.endswith("forward") else -1.0
        rows = []
        begin = t
        next_log = t
        while t < begin + length:
            elapsed = t - begin
            volts = direction * (1.0 * elapsed if test.startswith("quasistatic") else 7.0)
            # 1 kHz integration, Coulomb friction with a small smooth zone.
            dt = 0.001
            friction = ks * math.tanh(v / 0.01)
            gravity = kg * math.cos(q) if mechanism == "arm" else kg if mechanism == "elevator" else 0.0
            v += dt * (volts - friction - gravity - KV * v) / KA
            q += dt * v
            t += dt
            history.append((t, q, v))
            if len(history) > 100:
                del history[0]
            if t >= next_log:
                stamp = int(round(t * 1e6))
                logged_v = volts + rng.gauss(0.0, 0.02)
                age = rng.uniform(*latency) if latency[1] > 0.0 else 0.0
                _, q_then, v_then = min(history, key=lambda h: abs(h[0] - (t - age)))
                logged_q = round(q_then * scale / 1e-4) * 1e-4
                logged_w = (v_then + rng.gauss(0.0, 0.005)) * scale
                stamps = (stamp, stamp, stamp) if same_times else (stamp, stamp + 15, stamp + 31)
                log += record(ids["voltage-leader-" + mech], stamps[0], struct.pack("<d", logged_v))
                log += record(ids["position-leader-" + mech], stamps[1], struct.pack("<d", logged_q))
                log += record(ids["velocity-leader-" + mech], stamps[2], struct.pack("<d", logged_w))
                log += record(ids["voltage-follower-" + mech], stamp + 40, struct.pack("<d", logged_v))
                log += record(ids["position-follower-" + mech], stamp + 41, struct.pack("<d", -logged_q))
                log += record(ids["velocity-follower-" + mech], stamp + 42, struct.pack("<d", -logged_w))
                if not no_state:
                    log += record(ids["sysid-test-state-" + mech], stamp + 50, state_text(test).encode())
                log += record(ids["struct:Pose2d"], stamp + 60, bytes(24))
                rows.append((stamps[0], logged_v, logged_q, logged_w))
                next_log += 0.020 + rng.uniform(-0.004, 0.004)
        stamp = int(round(t * 1e6)) + 100
        if not no_state:
            log += record(ids["sysid-test-state-" + mech], stamp, state_text("none").encode())
        csv[test] = rows[1:]  # the last run of a test; its first loop precedes the state record
        # The mechanism coasts to rest between tests (not logged).
        v = 0.0
        t += 1.0
    log += finish(ids["struct:Pose2d"], int(t * 1e6))
    log += record(ids["struct:Pose2d"], int(t * 1e6) + 1, bytes(24))  # of a finished entry
    with open(out, "wb") as f:
        f.write(log)
    if prefix:
        for test, rows in csv.items():
            with open(prefix + test + ".csv", "w") as f:
                f.write("t,voltage,position,velocity\n")
                for stamp, a, b, c in rows:
                    f.write(f"{stamp // 1000000}.{stamp % 1000000:06d},{a!r},{b!r},{c!r}\n")  # the stamp exactly


if __name__ == "__main__":
    main()
