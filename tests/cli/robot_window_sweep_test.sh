#!/usr/bin/env bash
# robot --urdf at every window (issue 71: SIGFPE at --window 0.02-0.03 on a
# UR10e and 0.075-0.2 s on a 30 Hz bag): on the reference arm (5 ms steps,
# 20 s) and a 20 Hz copy of it, half windows from a tenth of a step to half
# the log either fit (exit 0) or are refused by name (exit 3 naming the
# window or the samples it leaves; exit 4 naming what the data do not
# determine), never a signal or another exit. Release suite only (label
# heavy: 25 fits).
# Usage: robot_window_sweep_test.sh DRIVETRAIN_FIT SERIAL_ARM_LOG SRC
set -u
bin="$1"
writer="$2"
src="$3"
program=drivetrain-fit
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
source "$src/tests/cli/cli_test_lib.sh"
"$writer" arm.urdf arm.csv 3 || { echo "FAIL: the reference writer"; exit 1; }
awk -F, 'NR == 1 || (NR - 2) % 10 == 0' arm.csv > arm20.csv
sweep() {  # LOG WINDOW...
  local log=$1 window code
  shift
  for window in "$@"; do
    "$bin" robot "$log" --urdf arm.urdf --window "$window" -q -o out.yaml > out.txt 2>&1
    code=$?
    case $code in
      0) ok ;;
      3) grep -q "window\|usable samples" out.txt && ok || fail "$log --window $window: exit 3 without the reason: $(cat out.txt)" ;;
      4) grep -q "not identifiable\|determine" out.txt && ok || fail "$log --window $window: exit 4: $(cat out.txt)" ;;
      *) fail "$log --window $window: exit $code: $(tail -c 400 out.txt)" ;;
    esac
  done
}
sweep arm.csv 0.0005 0.001 0.0025 0.005 0.0075 0.01 0.0125 0.015 0.02 0.05 0.1 0.5 2 5 10
sweep arm20.csv 0.005 0.05 0.075 0.1 0.12 0.2 0.5 2 5 10
finish
