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
grep -q "^  kp: {value: [0-9.e-]*, std: 0\.00[0-9]*[1-9]" gains.yaml && grep -q "^  kd: {value: " gains.yaml && ok ||
  fail "feedback section: $(cat gains.yaml)"
grep -q "correlation -0.500" gains.txt && ok || fail "the fit's correlation is not used: $(cat gains.txt)"
"$bin" report gains.yaml > report.txt 2>&1 && grep -q "feedback (position loop, preset wpilib" report.txt && ok ||
  fail "report of the feedback section: $(cat report.txt)"
"$bin" gains fitted.yaml --loop position -o again.yaml > /dev/null && cmp -s gains.yaml again.yaml && ok || fail "gains output differs between runs"
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
{ cat gains.yaml; echo "  kq: 3"; } > hostile.yaml
expect 3 "hostile.yaml:[0-9]+:[0-9]+: feedback.kq: unknown key" -- gains hostile.yaml
sed 's/^  loop: position/  loop: "x\\u002a\/"/' gains.yaml > loop.yaml
expect 3 "loop.yaml:[0-9]+:[0-9]+: feedback.loop" -- gains loop.yaml
finish
