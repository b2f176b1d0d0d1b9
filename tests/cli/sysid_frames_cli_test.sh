#!/usr/bin/env bash
# SysId-style logs with status-frame position and velocity (a 200 Hz jittered
# logger, 20 ms frames, quantised voltage, on the third flywheel the voltage
# in 10 ms frames of its own; generator sysid_status_frames.awk, written
# apart from the fit), fitted with defaults: each of Ks, Kv, Ka (and an arm's
# Kg) within 10 % of the truth and inside its 95 % interval, for a flywheel
# and an arm (docs/models.md#status-frames).
# Usage: sysid_frames_cli_test.sh DRIVETRAIN_FIT SRC
set -u
bin="$1"
src="$2"
program=drivetrain-fit
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
# shellcheck source=cli_test_lib.sh
. "$src/tests/cli/cli_test_lib.sh"

# check FILE NAME TRUTH: the estimate within 10 % of TRUTH and its ci95 holding it.
check() {
  awk -v name="$2" -v truth="$3" '
    $1 == name ":" && /ci95/ { gsub(/[{},\[\]]/, " "); value = $3; low = $7; high = $8 }
    END { rel = (value - truth) / truth; if (rel < 0) rel = -rel
          printf "%s %s = %s [%s, %s], truth %s\n", FILENAME, name, value, low, high, truth
          exit !(value != "" && rel <= 0.10 && low <= truth && truth <= high) }' "$1"
}

for seed in 1 2 3; do
  vframe=0; [ "$seed" = 3 ] && vframe=0.01
  awk -v kind=flywheel -v seed="$seed" -v vframe="$vframe" -f "$src/tests/cli/sysid_status_frames.awk" > "flywheel$seed.json"
  "$bin" axis "flywheel$seed.json" -o "flywheel$seed.yaml" > "flywheel$seed.txt" 2>&1 || fail "flywheel $seed: $(tail -3 "flywheel$seed.txt")"
  grep -q "method: output error (auto: status frames" "flywheel$seed.txt" && ok || fail "flywheel $seed: not fitted at the frames"
  if [ "$seed" = 3 ]; then
    grep -q "the effort of 2 logs comes in 1[0-9.]* ms frames too" "flywheel$seed.txt" && ok ||
      fail "the ramps' voltage frames not found: $(grep '^status frames' "flywheel$seed.txt")"
  fi
  for p in "coulomb 0.25" "viscous 0.12" "inertia 0.005"; do
    # shellcheck disable=SC2086
    check "flywheel$seed.yaml" $p > /dev/null && ok || fail "flywheel $seed: $(check "flywheel$seed.yaml" $p)"
  done
done
# Held-out logs are predicted by inverse dynamics: the rows as logged, and a warning that says so.
"$bin" axis flywheel1.json --validate flywheel2.json -o validated.yaml > validated.txt 2>&1 &&
  grep -q "warning: status frames: .* output error at the frames was not used (held-out logs are predicted by inverse dynamics)" validated.txt &&
  ok || fail "validation with status frames: $(grep -i 'warning\|^method' validated.txt | head -3)"
awk -v kind=arm -v seed=1 -f "$src/tests/cli/sysid_status_frames.awk" > arm.json
"$bin" axis arm.json -o arm.yaml > arm.txt 2>&1 || fail "arm: $(tail -3 arm.txt)"
grep -q "status frames: the position of 4 of 4 logs" arm.txt && ok || fail "arm: the 1 s step logs not found held: $(grep 'status frames' arm.txt)"
grep -q "systematic errors in the intervals" arm.txt && ok || fail "arm: no timing errors in the intervals"
for p in "coulomb 0.3" "viscous 1.5" "inertia 0.08" "gravity_cos 0.6"; do
  # shellcheck disable=SC2086
  check arm.yaml $p > /dev/null && ok || fail "arm: $(check arm.yaml $p)"
done
finish
