#!/usr/bin/env bash
# drivetrain-fit gains (docs/models.md#feedback-gains): SysId's published
# gains through the command line; position gains with and without a 10 ms
# delay against a discrete Riccati solution computed here independently
# (numpy: the stable eigenvectors of the symplectic matrix, the plant's ZOH
# in closed form; SciPy's solve_discrete_are too where it is installed);
# the std from a fit's covariance; the feedback section written, read back
# and reported; refusals by name.
# Usage: gains_cli_test.sh DRIVETRAIN_FIT SOURCE_DIR
set -u
bin="$1"
src="$2"
program=drivetrain-fit
# shellcheck source=cli_test_lib.sh
source "$(dirname "$0")/cli_test_lib.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1

# WPILib SysId's test values (max velocity error 1.5, max effort 7, 0.02 s).
"$bin" gains --kv 3.060 --ka 0.327 --json > v1.json && grep -q '"kp":{"value":2\.1[01]' v1.json && ok || fail "Kp 2.11: $(cat v1.json)"
"$bin" gains --kv 0.0693 --ka 0.1170 --json > v2.json && grep -q '"kp":{"value":3\.1[01]' v2.json && ok || fail "Kp 3.11: $(cat v2.json)"

# Two published SysId summaries (docs/models.md#feedback-gains) from a parameter
# file with their Ks, Kv, Ka in volts, no weights given: SysId's GUI sets the
# maximum velocity error to (12 - Ks) / (4 Kv) on loading data (1.0863 and
# 1.2802 in the summaries), and the velocity kp is SysId's; the position
# gains with the summaries' maximum position error 0.125 (an older GUI's
# default; today's sets 0.1, which driveid takes).
for case in "-0.19471 2.8065 0.59435 1.0863 3.7416 48.995 7.128" "0.12977 2.3181 0.2372 1.2802 2.7912 44.437 4.4068"; do
  set -- $case
  printf 'axis:\n  inertia: %s\n  viscous: %s\nfeedforward:\n  effort_unit: V\n  position_unit: Rotations\n  Ks: {value: %s}\n  Kv: {value: %s}\n  Ka: {value: %s}\n' \
    "$3" "$2" "$1" "$2" "$3" > sysid.yaml
  "$bin" gains sysid.yaml --json > sv.json || fail "gains sysid.yaml $case"
  "$bin" gains sysid.yaml > sv.txt 2>&1
  "$bin" gains sysid.yaml --loop position --max-position-error 0.125 --json > sp.json || fail "position gains $case"
  /usr/bin/python3 - "$4" "$5" "$6" "$7" sv.json sp.json <<'PY' && ok || fail "SysId's published gains $case: $(cat sv.json)"
import json, sys
qv, kp, pkp, pkd = map(float, sys.argv[1:5])
v = json.load(open(sys.argv[5]))
p = json.load(open(sys.argv[6]))
def value(j, key):
    for section in (j, j.get("feedback", {}), j.get("settings", {})):
        if key in section:
            x = section[key]
            return x["value"] if isinstance(x, dict) else x
    raise KeyError(key)
assert abs(value(v, "max_velocity_error") - qv) < 1e-4 * qv, value(v, "max_velocity_error")
assert abs(value(v, "kp") - kp) < 1e-4 * kp, value(v, "kp")
assert abs(value(p, "kp") - pkp) < 1e-4 * pkp and abs(value(p, "kd") - pkd) < 1e-4 * pkd, (value(p, "kp"), value(p, "kd"))
PY
  grep -q "note: LQR weights as SysId's GUI sets them on loading data" sv.txt && ok || fail "the weights' note: $(cat sv.txt)"
done

py=python3
/usr/bin/python3 -c "import numpy" 2> /dev/null && py=/usr/bin/python3  # Debian's, not a pyenv shim's
if "$py" -c "import numpy" 2> /dev/null; then
  for case in "3.060 0.327 0" "3.060 0.327 0.01" "0.0693 0.1170 0.01" "0.18 0.0035 0" "0.18 0.0035 0.01"; do
    set -- $case
    "$bin" gains --loop position --kv "$1" --ka "$2" --delay "$3" --max-position-error 0.2 --json > pos.json || fail "gains $case"
    "$py" - "$1" "$2" "$3" pos.json <<'PY' && ok || fail "position gains $case differ from the independent Riccati solution"
import json, sys
import numpy as np
kv, ka, delay = map(float, sys.argv[1:4])
got = json.load(open(sys.argv[4]))["feedback"]
T, qp, qv, r = 0.02, 0.2, 1.5, 7.0
a = kv / ka
e = np.exp(-a * T)
A = np.array([[1.0, (1 - e) / a], [0.0, e]])
B = np.array([[(T - (1 - e) / a) / ka / a], [(1 - e) / ka / a]])
Q = np.diag([1 / qp**2, 1 / qv**2]); R = np.array([[1 / r**2]])
# DARE from the symplectic matrix: the stable eigenvectors [X1; X2], P = X2 X1^-1.
Ai = np.linalg.inv(A); G = B @ np.linalg.inv(R) @ B.T
Z = np.block([[A + G @ Ai.T @ Q, -G @ Ai.T], [-Ai.T @ Q, Ai.T]])
w, v = np.linalg.eig(Z)
s = v[:, np.abs(w) < 1]
P = np.real(s[2:] @ np.linalg.inv(s[:2]))
try:
    from scipy.linalg import solve_discrete_are
    assert np.allclose(P, solve_discrete_are(A, B, Q, R), rtol=1e-6), "scipy disagrees"
    print("scipy cross-check done")
except ImportError:
    pass
K = np.linalg.solve(R + B.T @ P @ B, B.T @ P @ A)
if delay > 0:
    w, v = np.linalg.eig(A - B @ K)
    K = np.real(K @ v @ np.diag(w.astype(complex) ** (delay / T)) @ np.linalg.inv(v))
ok = abs(got["kp"]["value"] / K[0, 0] - 1) < 0.01 and abs(got["kd"]["value"] / K[0, 1] - 1) < 0.01
print(kv, ka, delay, got["kp"]["value"], K[0, 0], got["kd"]["value"], K[0, 1])
sys.exit(0 if ok else 1)
PY
  done
else
  echo "skipped: python3 with numpy is not installed (the independent Riccati cross-check)"
fi

# A velocity loop's weight given alone (there is no position weight to give).
"$bin" gains --kv 2.5 --ka 0.3 --max-velocity-error 1 --max-effort 7 --json > only_v.json 2> only_v.txt &&
  grep -q '"max_velocity_error":1\.0,' only_v.json && ok || fail "a velocity weight given alone: $(cat only_v.txt only_v.json)"
# From a fitted file: Kv, Ka, their stds and the fit's correlation.
cat > fitted.yaml <<'YAML'
axis:
  inertia: 0.0035
  viscous: 0.18
feedforward:
  law: axis
  effort_unit: "V"
  position_unit: "Radians"
  Ks: {value: 0.02, std: 0.008}
  Kv: {value: 0.18, std: 0.0006}
  Ka: {value: 0.0035, std: 0.00015}
fit:
  estimates:
    inertia: {value: 0.0035, std: 0.00015}
    viscous: {value: 0.18, std: 0.0006}
  correlation:
    inertia: [1.0000, -0.5000]
    viscous: [-0.5000, 1.0000]
YAML
"$bin" gains fitted.yaml --loop position -o gains.yaml > gains.txt 2>&1 || fail "gains from a file: $(cat gains.txt)"
grep -q "^  kp: {value: [0-9.e-]*, std: 0\.[0-9]*[1-9]" gains.yaml && grep -q "^  kd: {value: " gains.yaml && ok ||
  fail "feedback section: $(cat gains.yaml)"
grep -q "correlation -0.500" gains.txt && ok || fail "the fit's correlation is not used: $(cat gains.txt)"
# Each gain's 95 % interval, sampled over the fit's covariance (not +- 1.96
# std: kp is not linear in Ka), holds the value, in the file, the table and
# the JSON alike; a file with it reads back.
awk '/^  kp: \{value: / { gsub(/[{},:\[\]]/, " "); v = $3; lo = $7; hi = $8; exit !(lo < v && v < hi && lo > 0) }' gains.yaml &&
  grep -q "^  kp .* +- .*  95 % \[[0-9.e-]*, [0-9.e-]*\]$" gains.txt && ok || fail "the gains' interval: $(grep kp gains.yaml gains.txt)"
"$bin" gains fitted.yaml --loop position --json > gains_ci.json && grep -q '"kp":{"value":[^}]*"ci95":\[' gains_ci.json && ok ||
  fail "the gains' interval in JSON: $(head -c 400 gains_ci.json)"
sed 's/^\(  kp: {value: [^,]*, std: [^,]*\), ci95: \[[^]]*\]/\1, ci95: [1e9, 2e9]/' gains.yaml > bad_ci.yaml
expect 3 "bad_ci.yaml:[0-9]+:[0-9]+: feedback.kp.ci95: \[1000000000, 2000000000\] does not hold the value" -- gains bad_ci.yaml
"$bin" report gains.yaml > report.txt 2>&1 && grep -q "feedback (position loop, preset wpilib" report.txt && ok ||
  fail "report of the feedback section: $(cat report.txt)"
"$bin" gains fitted.yaml --loop position -o again.yaml > /dev/null && cmp -s gains.yaml again.yaml && ok || fail "gains output differs between runs"
# The written file keeps the fit it was designed from, as it was.
diff <(sed -n '/^fit:/,$p' fitted.yaml) <(sed -n '/^fit:/,$p' gains.yaml) > /dev/null && grep -q "^fit:" gains.yaml && ok ||
  fail "the fit section is not kept: $(grep -n '^[a-z]' gains.yaml)"
"$bin" gains gains.yaml --loop position --json > reread.json && grep -q '"loop":"position"' reread.json && ok ||
  fail "the gains output does not read back as gains input"

# Refusals and bad input.
expect 2 "--preset 'nope': one of wpilib" -- gains fitted.yaml --preset nope
expect 3 "paper000.yaml: no 'feedforward' or 'axis' section" -- gains "$src/data/paper000.yaml"
sed 's/Ka: {value: 0.0035/Ka: {value: -0.0035/' fitted.yaml > negative.yaml
expect 4 "LQR gains need Kv >= 0 and Ka > 0" -- gains negative.yaml
sed 's/"V"/"N m"/' fitted.yaml > torque.yaml
expect 2 "--preset rev-neo converts volts to its output, but the effort is in N m" -- gains torque.yaml --preset rev-neo
expect 2 "gains needs a parameter file or both --kv and --ka" -- gains --kv 1
# Vendor units: Phoenix 6 and REV work in rotations, so a log in radians is
# converted (2 pi rad per rotation: the same as --conversion 1/(2 pi)); a
# unit that is no angle, or Phoenix 5's sensor units, must be given.
"$bin" gains fitted.yaml --loop position --preset ctre-phoenix6 --json > p6.json &&
  "$bin" gains fitted.yaml --loop position --preset ctre-phoenix6 --conversion 0.15915494309189535 --json > p6c.json &&
  cmp -s p6.json p6c.json && grep -q '"position_unit":"rotation"' p6.json && grep -q '"unit":"V/rotation"' p6.json && ok ||
  fail "phoenix6 from radians: $(head -c 500 p6.json)"
sed 's/"Radians"/"Meters"/' fitted.yaml > meters.yaml
expect 2 "--preset ctre-phoenix6 works in rotations, and the file's position unit is 'Meters': give --conversion" -- gains meters.yaml --preset ctre-phoenix6
expect 2 "--preset ctre-phoenix5 works in the sensor's units: give --conversion" -- gains fitted.yaml --preset ctre-phoenix5
# A delay that leaves no useful gain is named (the gain stays printed).
"$bin" gains --kv 1 --ka 0.001 --loop velocity --period 0.001 --delay 0.5 --json > weak.json 2> weak.txt &&
  grep -q "measurement delay" weak.txt && grep -q '"warnings":\["kp = ' weak.json && ok || fail "a useless gain: $(cat weak.txt)"
"$bin" gains --kv 1 --ka 0.001 --loop velocity --period 0.001 --delay 0.001 > strong.txt 2>&1 && ! grep -q "warning" strong.txt && ok ||
  fail "a useful gain warned: $(cat strong.txt)"
sed "/^feedback:/a\\  kq: 3" gains.yaml > hostile.yaml
expect 3 "hostile.yaml:[0-9]+:[0-9]+: feedback.kq: unknown key" -- gains hostile.yaml
sed 's/^  loop: position/  loop: "x\\u002a\/"/' gains.yaml > loop.yaml
expect 3 "loop.yaml:[0-9]+:[0-9]+: feedback.loop" -- gains loop.yaml
expect 2 "--plot applies to --loop speed" -- gains fitted.yaml --plot gains.svg
expect 3 "fitted.yaml: no 'joint' section for a speed loop" -- gains fitted.yaml --loop speed
finish
